// The size bound of the server's disk caches: the oldest use goes first.
#include "LeastRecentlyUsed.h"

#include <algorithm>

namespace vots::server {

void trimLeastRecentlyUsed(std::vector<CachedOnDisk> cached, std::uint64_t budget,
                           const std::filesystem::path& keep,
                           const std::function<bool(const CachedOnDisk&)>& remove) {
    std::uint64_t total = 0;
    for (const CachedOnDisk& c : cached)
        total += c.bytes;
    std::sort(cached.begin(), cached.end(),
              [](const CachedOnDisk& a, const CachedOnDisk& b) { return a.used < b.used; });
    for (const CachedOnDisk& c : cached) {
        if (total <= budget) break;
        if (c.path == keep) continue;
        if (remove(c)) total -= c.bytes;
    }
}

} // namespace vots::server
