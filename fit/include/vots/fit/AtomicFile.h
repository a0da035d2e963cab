// Writing a whole file so that readers see the old file or the new one, never half of one (POSIX).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>

namespace vots::fit {

/// Runs between 1 MiB pieces of a write: there a background writer can wait while foreground work runs
/// (copying into the page cache costs CPU even at nice 19). Empty: the bytes go in one write.
using BetweenChunks = std::function<void()>;

/// A name beside `path` that no other writer uses: "<path>.tmp-<pid>-<n>", n counting this process's
/// temporaries, so two threads writing the same path never share one.
std::string uniqueTemporaryPath(const std::string& path);

/// Writes `bytes` to a new uniquely named temporary beside `path`, fsyncs and closes it, and returns its
/// name; the caller publishes it (publishTemporary) or removes it. On failure the temporary is removed and
/// InputError ("cannot write '<path>': <reason>") thrown.
std::string writeTemporaryFor(const std::string& path, std::span<const std::uint8_t> bytes,
                              const BetweenChunks& betweenChunks = {});

/// Makes a written and synced temporary the file `path`: renames it over path (readers see the old file
/// or the new one) and syncs the folder, so the rename survives a crash. Removes the temporary and throws
/// InputError when it cannot.
void publishTemporary(const std::string& temporary, const std::string& path);

/// writeTemporaryFor, then publishTemporary: a crash or a failure leaves the old file (or none) under
/// `path`, and no temporary.
void writeFileAtomically(const std::string& path, std::span<const std::uint8_t> bytes,
                         const BetweenChunks& betweenChunks = {});

} // namespace vots::fit
