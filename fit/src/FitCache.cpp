// FitCache: remembers every box fitted for one volume/degree/certify so a new eps reuses the work.
#include "FitCacheImpl.h"

#include "SampleAccess.h"

#include <cmath>

namespace vots::fit {

FitCache::FitCache() : mImpl(std::make_unique<Impl>()) {}
FitCache::~FitCache() = default;
std::size_t FitCache::size() const {
    return mImpl->size();
}
std::size_t FitCache::memoryBytes() const {
    return mImpl->memoryBytes();
}

void FitCache::Impl::bind(const Volume& volume, int degreeIn, Certify certifyIn, FitNorm normIn) {
    if (volumeData == sampleData(volume) && dims == volume.dims && degree == degreeIn &&
        certify == certifyIn && norm == normIn)
        return;
    for (auto& shard : shards) {
        std::lock_guard lock(shard.mutex);
        shard.index.clear();
        shard.entries.clear();
        shard.minimaxes.clear();
    }
    {
        std::lock_guard lock(maskMutex);
        mask.reset();
    }
    volumeData = sampleData(volume);
    dims = volume.dims;
    degree = degreeIn;
    certify = certifyIn;
    norm = normIn;
}

std::shared_ptr<const CellMask> FitCache::Impl::maskFor(const Volume& volume, std::optional<float> background,
                                                        std::optional<float> noDataValue) {
    std::lock_guard lock(maskMutex);
    if (!mask || maskBackground != background || maskNoData != noDataValue) {
        mask = std::make_shared<const CellMask>(volume, background, noDataValue);
        maskBackground = background;
        maskNoData = noDataValue;
    }
    return mask;
}

std::optional<CachedBox> FitCache::Impl::find(const Box& box) {
    auto& shard = shards[shardOf(box)];
    std::lock_guard lock(shard.mutex);
    const auto it = shard.index.find(box);
    if (it == shard.index.end()) return std::nullopt;
    return shard.entries[it->second];
}

void FitCache::Impl::prefetch(const Box& box) {
    auto& shard = shards[shardOf(box)];
    std::lock_guard lock(shard.mutex);
    shard.index.prefetch(box);
}

void FitCache::Impl::store(const Box& box, const CachedBox& entry) {
    auto& shard = shards[shardOf(box)];
    std::lock_guard lock(shard.mutex);
    const auto [it, added] = shard.index.try_emplace(box, static_cast<std::uint32_t>(shard.entries.size()));
    if (added)
        shard.entries.push_back(entry);
    else
        shard.entries[it->second] = entry;
}

void FitCache::Impl::find(const Box& box, BoxRecord& record) {
    auto& shard = shards[shardOf(box)];
    std::lock_guard lock(shard.mutex);
    const auto it = shard.index.find(box);
    if (it == shard.index.end()) return;
    const CachedBox& entry = shard.entries[it->second];
    record.lsq = entry.outcome;
    record.fitted = entry.hasCoefficients;
    record.lowerBound = entry.lowerBound;
    record.state = entry.minimaxState;
    if (entry.minimaxEntry != CachedBox::NO_ENTRY) {
        const CachedMinimax& found = shard.minimaxes[entry.minimaxEntry];
        record.minimax = found.outcome;
        record.centredHalfRange = found.centredHalfRange;
        record.centredConstant = found.centredConstant;
    }
}

void FitCache::Impl::store(const Box& box, const BoxRecord& record) {
    auto& shard = shards[shardOf(box)];
    std::lock_guard lock(shard.mutex);
    const auto [it, added] = shard.index.try_emplace(box, static_cast<std::uint32_t>(shard.entries.size()));
    if (added) shard.entries.emplace_back();
    CachedBox& entry = shard.entries[it->second];
    entry.outcome = record.lsq;
    entry.hasCoefficients = record.fitted;
    entry.lowerBound = record.lowerBound;
    // What the least-change search found holds at its own eps only (BoxRecord::Minimax::Found): not kept.
    const bool centred = record.state == BoxRecord::Minimax::Centred;
    entry.minimaxState = centred ? BoxRecord::Minimax::Centred : BoxRecord::Minimax::NotRun;
    if (!std::isnan(record.centredHalfRange)) {
        const CachedMinimax found{centred ? record.minimax : BoxOutcome{}, record.centredHalfRange,
                                  record.centredConstant};
        if (entry.minimaxEntry == CachedBox::NO_ENTRY) {
            entry.minimaxEntry = static_cast<std::uint32_t>(shard.minimaxes.size());
            shard.minimaxes.push_back(found);
        } else {
            shard.minimaxes[entry.minimaxEntry] = found;
        }
    }
}

std::size_t FitCache::Impl::size() {
    std::size_t n = 0;
    for (auto& shard : shards) {
        std::lock_guard lock(shard.mutex);
        n += shard.index.size();
    }
    return n;
}

std::size_t FitCache::Impl::memoryBytes() {
    // The index's slots (a control byte and a box -> entry pair each, at its capacity) and the entries.
    constexpr std::size_t SLOT = 1 + sizeof(std::pair<Box, std::uint32_t>);
    std::size_t bytes = sizeof(Impl);
    for (auto& shard : shards) {
        std::lock_guard lock(shard.mutex);
        bytes += shard.index.capacity() * SLOT + shard.entries.size() * sizeof(CachedBox) +
                 shard.minimaxes.size() * sizeof(CachedMinimax);
    }
    std::lock_guard lock(maskMutex);
    if (mask) bytes += mask->memoryBytes();
    return bytes;
}

} // namespace vots::fit
