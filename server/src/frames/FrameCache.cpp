// FrameCache: an LRU of encoded frames plus the renders in flight that identical requests can join.
#include "frames/FrameCache.h"

namespace vots::server {

namespace {
constexpr int MAX_JOINS = 3; // after this many failed shared renders, render without joining
}

FrameCache::FrameCache(std::size_t budgetBytes) : mBudget(budgetBytes) {}

std::shared_ptr<const FrameCache::Frame>
FrameCache::get(const std::string& key, const std::function<Frame()>& render, Source* source) {
    for (int joins = 0;; ++joins) {
        std::shared_future<FramePtr> inFlight;
        std::promise<FramePtr> mine;
        bool registered = false; // mine is the render identical requests join
        {
            std::lock_guard lock(mMutex);
            if (const auto it = mIndex.find(key); it != mIndex.end()) {
                mLru.splice(mLru.begin(), mLru, it->second);
                ++mCached;
                if (source) *source = Source::Cached;
                return it->second->frame;
            }
            if (const auto running = mInFlight.find(key); running == mInFlight.end()) {
                mInFlight.emplace(key, mine.get_future().share());
                registered = true;
            } else if (joins < MAX_JOINS) {
                inFlight = running->second;
            }
        }
        if (inFlight.valid()) {
            FramePtr frame = inFlight.get();
            if (!frame) continue; // its failure was its own: look again, and render if nobody else does
            std::lock_guard lock(mMutex);
            ++mShared;
            if (source) *source = Source::Shared;
            return frame;
        }
        try {
            auto frame = std::make_shared<const Frame>(render());
            std::lock_guard lock(mMutex);
            if (registered) mInFlight.erase(key);
            keepLocked(key, frame);
            ++mRendered;
            if (source) *source = Source::Rendered;
            if (registered) mine.set_value(frame);
            return frame;
        } catch (...) {
            {
                std::lock_guard lock(mMutex);
                if (registered) mInFlight.erase(key);
            }
            // Joiners learn of the failure as no frame: the exception object stays on this thread
            // (one shared across threads is freed where ThreadSanitizer cannot see the ordering).
            if (registered) mine.set_value(nullptr);
            throw;
        }
    }
}

void FrameCache::keepLocked(const std::string& key, FramePtr frame) {
    const std::size_t bytes = frame->png.size() + key.size();
    if (bytes > mBudget || mIndex.count(key)) return;
    mLru.push_front({key, std::move(frame)});
    mIndex[key] = mLru.begin();
    mBytes += bytes;
    while (mBytes > mBudget) {
        const Entry& last = mLru.back();
        mBytes -= last.frame->png.size() + last.key.size();
        mIndex.erase(last.key);
        mLru.pop_back();
    }
}

FrameCache::Summary FrameCache::summary() const {
    std::lock_guard lock(mMutex);
    return {mLru.size(), mBytes, mBudget, mRendered, mShared, mCached};
}

} // namespace vots::server
