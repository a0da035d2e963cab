// FitCache: remembers every box fitted for one volume/degree/certify so a new eps reuses the work.
#include "FitCacheImpl.h"

namespace vots::fit {

FitCache::FitCache() : mImpl(std::make_unique<Impl>()) {}
FitCache::~FitCache() = default;
std::size_t FitCache::size() const {
    return mImpl->size();
}

void FitCache::Impl::bind(const Volume& volume, int degreeIn, Certify certifyIn) {
    if (volumeData == volume.values.data() && dims == volume.dims && degree == degreeIn &&
        certify == certifyIn)
        return;
    for (auto& shard : shards) {
        std::lock_guard lock(shard.mutex);
        shard.boxes.clear();
    }
    volumeData = volume.values.data();
    dims = volume.dims;
    degree = degreeIn;
    certify = certifyIn;
}

std::optional<CachedBox> FitCache::Impl::find(const Box& box) {
    auto& shard = shards[(BoxHash{}(box) >> 32) % SHARDS];
    std::lock_guard lock(shard.mutex);
    const auto it = shard.boxes.find(box);
    if (it == shard.boxes.end()) return std::nullopt;
    return it->second;
}

void FitCache::Impl::store(const Box& box, const CachedBox& entry) {
    auto& shard = shards[(BoxHash{}(box) >> 32) % SHARDS];
    std::lock_guard lock(shard.mutex);
    shard.boxes[box] = entry;
}

std::size_t FitCache::Impl::size() {
    std::size_t n = 0;
    for (auto& shard : shards) {
        std::lock_guard lock(shard.mutex);
        n += shard.boxes.size();
    }
    return n;
}

} // namespace vots::fit
