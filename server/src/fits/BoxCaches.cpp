// BoxCaches: fit::FitCache by "dataset/frame/degree", least recently used first out over the budget.
#include "fits/BoxCaches.h"

#include <algorithm>

namespace vots::server {

std::shared_ptr<fit::FitCache> BoxCaches::forFits(const std::string& dataset, int frame, int degree) {
    const std::string name = dataset + "/" + std::to_string(frame) + "/" + std::to_string(degree);
    std::lock_guard lock(mMutex);
    auto it = std::find_if(mKept.begin(), mKept.end(), [&](const Kept& k) { return k.name == name; });
    if (it == mKept.end())
        mKept.push_front({name, std::make_shared<fit::FitCache>(), 0});
    else
        mKept.splice(mKept.begin(), mKept, it);
    // Counted here, once per cache, at a fit's start: between fits a cache does not grow, and a fit running
    // now (a warm-up beside a requested fit) is counted at the next one.
    mBytes = 0;
    for (Kept& k : mKept)
        mBytes += k.bytes = k.cache->memoryBytes();
    while (mKept.size() > MAX_KEPT || (mKept.size() > 1 && mBytes > mBudget)) {
        mBytes -= mKept.back().bytes;
        mKept.pop_back();
        ++mDropped;
    }
    Kept& asked = mKept.front();
    if (mBytes > mBudget) {
        mBytes -= asked.bytes;
        asked.cache = std::make_shared<fit::FitCache>();
        mBytes += asked.bytes = asked.cache->memoryBytes();
        ++mDropped;
    }
    return asked.cache;
}

BoxCacheStats BoxCaches::stats() const {
    std::lock_guard lock(mMutex);
    return {mKept.size(), mBytes, mBudget, mDropped};
}

} // namespace vots::server
