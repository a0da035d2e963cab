// Vot-Space file version 1 (docs/DESIGN.md §8): exact byte layout, CRC-32, atomic write.
#pragma once

#include "vots/fit/VotSpace.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vots::fit {

inline constexpr std::uint32_t VOTS_FILE_VERSION = 1;
inline constexpr std::size_t VOTS_HEADER_BYTES = 128;
inline constexpr std::size_t VOTS_RECORD_BYTES = 120;

/// Serialises to the exact v1 byte layout (header, records, meta JSON, CRC-32).
std::vector<std::uint8_t> encodeVotSpace(const VotSpace& space);
/// Parses and validates v1 bytes; throws InputError naming the first problem found
/// (magic, version, header size, length/count mismatch, CRC, box outside grid, lo >= hi, non-finite).
VotSpace decodeVotSpace(const std::uint8_t* data, std::size_t size);

/// Writes to "<path>.tmp-<pid>-<n>" (n counts the process's writes), fsyncs, then renames over path, so a
/// crash never leaves a half-written file under the real name. Throws InputError when the folder is not
/// writable. betweenChunks, when given, runs between 1 MiB pieces of the write: there a background writer can
/// wait while foreground work runs (copying into the page cache costs CPU even at nice 19).
void writeVotSpaceFile(const std::string& path, const VotSpace& space,
                       const std::function<void()>& betweenChunks = {});
/// Reads and validates a file; throws InputError with the path in the message.
VotSpace readVotSpaceFile(const std::string& path);

} // namespace vots::fit
