// Keeping a folder of cached things (fits, retrieved series) within a size bound: the least recently used go
// first.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

namespace vots::server {

/// One cached thing on disk.
struct CachedOnDisk {
    std::filesystem::path path;
    std::filesystem::file_time_type used; // last written or opened
    std::uint64_t bytes = 0;
};

/// Removes things, least recently used first, until the rest total at most `budget` bytes; `keep` (the
/// one just written) stays whatever its size. `remove` removes one and says whether it went (another
/// process may have removed it first).
void trimLeastRecentlyUsed(std::vector<CachedOnDisk> cached, std::uint64_t budget,
                           const std::filesystem::path& keep,
                           const std::function<bool(const CachedOnDisk&)>& remove);

} // namespace vots::server
