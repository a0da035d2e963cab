// BoxCaches: fit::FitCache by "dataset/frame/degree", least recently used first out over the budget.
#include "fits/BoxCaches.h"

#include <algorithm>

namespace vots::server {

std::shared_ptr<fit::FitCache> BoxCaches::forFits(const std::string& dataset, int frame, int degree) {
    const std::string name = dataset + "/" + std::to_string(frame) + "/" + std::to_string(degree);
    std::lock_guard lock(mMutex);
    auto it = std::find_if(mKept.begin(), mKept.end(), [&](const Kept& k) { return k.name == name; });
    if (it == mKept.end())
        mKept.push_front({name, std::make_shared<fit::FitCache>()});
    else
        mKept.splice(mKept.begin(), mKept, it);
    // Counted here, at a fit's start: between fits a cache does not grow, and a fit running now (a
    // warm-up beside a requested fit) is counted at the next one.
    const auto total = [&] {
        std::uint64_t bytes = 0;
        for (const Kept& k : mKept)
            bytes += k.cache->memoryBytes();
        return bytes;
    };
    mBytes = total();
    while (mKept.size() > MAX_KEPT || (mKept.size() > 1 && mBytes > mBudget)) {
        mKept.pop_back();
        ++mDropped;
        mBytes = total();
    }
    if (mBytes > mBudget) {
        mKept.front().cache = std::make_shared<fit::FitCache>();
        ++mDropped;
        mBytes = total();
    }
    return mKept.front().cache;
}

BoxCacheStats BoxCaches::stats() const {
    std::lock_guard lock(mMutex);
    return {mKept.size(), mBytes, mBudget, mDropped};
}

} // namespace vots::server
