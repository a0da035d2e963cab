// BoxCaches: a small map of fit::FitCache by "dataset/frame/degree", trimmed when a new one is made.
#include "fits/BoxCaches.h"

#include <iterator>

namespace vots::server {

std::shared_ptr<fit::FitCache> BoxCaches::forFits(const std::string& dataset, int frame, int degree) {
    const std::string name = dataset + "/" + std::to_string(frame) + "/" + std::to_string(degree);
    std::lock_guard lock(mMutex);
    auto& slot = mCaches[name];
    if (!slot) {
        slot = std::make_shared<fit::FitCache>();
        if (mCaches.size() > MAX_KEPT)
            mCaches.erase(mCaches.begin()->first == name ? std::next(mCaches.begin()) : mCaches.begin());
    }
    return slot;
}

} // namespace vots::server
