// VotSpaceCache: memory in front of the folder; disk hits enter memory, writes go now or later.
#include "fits/VotSpaceCache.h"

namespace vots::server {

VotSpaceCache::VotSpaceCache(std::filesystem::path cacheDir, std::size_t memoryBudgetBytes,
                             std::uint64_t diskBudgetBytes)
    : mMemory(memoryBudgetBytes), mDisk(std::move(cacheDir), diskBudgetBytes),
      mWriter(mDisk, memoryBudgetBytes) {}

std::shared_ptr<const fit::VotSpace> VotSpaceCache::findInMemory(const FitKey& key) {
    return mMemory.find(key.text());
}

std::shared_ptr<const fit::VotSpace> VotSpaceCache::find(const FitKey& key) {
    if (auto space = findInMemory(key)) return space;
    auto space = mDisk.read(key);
    if (space) mMemory.insert(key.text(), space);
    return space;
}

void VotSpaceCache::store(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    storeInMemory(key, space);
    storeOnDisk(key, *space);
}

void VotSpaceCache::storeInMemory(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    mMemory.insert(key.text(), std::move(space));
}

void VotSpaceCache::storeOnDisk(const FitKey& key, const fit::VotSpace& space) {
    mDisk.write(key, space);
}

void VotSpaceCache::storeOnDiskLater(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    if (mDisk.enabled()) mWriter.post(key, std::move(space));
}

} // namespace vots::server
