// Writing a whole file so that readers never see half of it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vots::render {

/// Writes "<path>.tmp-<pid>" and renames it over path. Throws vots::fit::InputError when the file
/// cannot be written; no temporary file is left behind then.
void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// The temporary name writeFileAtomically uses for path.
std::string temporaryNameFor(const std::string& path);

} // namespace vots::render
