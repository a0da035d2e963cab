// Tasks run one at a time on a thread at the lowest CPU priority (nice 19), in the order posted.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace vots::server {

/// For work nobody waits for (cache files): it must not slow a fit or a frame that someone is waiting
/// for. Nice 19, not SCHED_IDLE: it still progresses on a busy machine.
class LowPriorityQueue {
public:
    explicit LowPriorityQueue(std::size_t maxPending);
    ~LowPriorityQueue(); // runs what is still pending, then joins
    LowPriorityQueue(const LowPriorityQueue&) = delete;
    LowPriorityQueue& operator=(const LowPriorityQueue&) = delete;

    /// Queues a task; returns false (and drops it) when maxPending tasks are already waiting. A task
    /// must not throw.
    bool post(std::function<void()> task);
    /// Waits until every task posted so far has run.
    void drain();

private:
    void loop();

    const std::size_t mMaxPending;
    std::mutex mMutex;
    std::condition_variable mWake, mIdle;
    std::deque<std::function<void()>> mTasks;
    bool mRunning = false; // a task is running
    bool mStopping = false;
    std::thread mThread;
};

} // namespace vots::server
