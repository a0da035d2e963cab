// LowPriorityQueue: one nice-19 worker thread over a FIFO of tasks.
#include "fits/LowPriorityQueue.h"

#include "vots/server/ThreadPriority.h"

namespace vots::server {

LowPriorityQueue::LowPriorityQueue(std::size_t maxPending)
    : mMaxPending(maxPending), mThread([this] { loop(); }) {}

LowPriorityQueue::~LowPriorityQueue() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
    }
    mWake.notify_all();
    mThread.join();
}

bool LowPriorityQueue::post(std::function<void()> task) {
    {
        std::lock_guard lock(mMutex);
        if (mTasks.size() >= mMaxPending) return false;
        mTasks.push_back(std::move(task));
    }
    mWake.notify_one();
    return true;
}

void LowPriorityQueue::drain() {
    std::unique_lock lock(mMutex);
    mIdle.wait(lock, [this] { return mTasks.empty() && !mRunning; });
}

void LowPriorityQueue::loop() {
    lowerThisThreadToNice19();
    std::unique_lock lock(mMutex);
    for (;;) {
        mWake.wait(lock, [this] { return mStopping || !mTasks.empty(); });
        if (mTasks.empty()) return; // stopping, and nothing left to run
        std::function<void()> task = std::move(mTasks.front());
        mTasks.pop_front();
        mRunning = true;
        lock.unlock();
        task();
        lock.lock();
        mRunning = false;
        if (mTasks.empty()) mIdle.notify_all();
    }
}

} // namespace vots::server
