// StreamThreads: one thread per long-lived answer (a Server-Sent Events stream), beside the worker pool,
// so that watchers never hold a worker; bounded in number.
#pragma once

#include <cstddef>
#include <functional>
#include <list>
#include <mutex>
#include <thread>

namespace vots::server {

/// Thread-safe.
class StreamThreads {
public:
    explicit StreamThreads(std::size_t maxThreads) : mMax(maxThreads) {}
    ~StreamThreads() { joinAll(); }
    StreamThreads(const StreamThreads&) = delete;
    StreamThreads& operator=(const StreamThreads&) = delete;

    /// Runs fn on a new thread; false (fn not run) when maxThreads are running or after joinAll().
    bool tryStart(std::function<void()> fn);
    /// Waits for every thread; later tryStart() calls fail.
    void joinAll();
    std::size_t running() const;

private:
    struct Entry {
        std::thread thread;
        bool finished = false;
    };
    void reapLocked();

    const std::size_t mMax;
    mutable std::mutex mMutex;
    std::list<Entry> mEntries;
    std::size_t mRunning = 0;
    bool mClosed = false;
};

} // namespace vots::server
