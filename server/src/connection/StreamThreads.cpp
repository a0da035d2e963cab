// StreamThreads: starts a thread per stream and joins finished ones as new ones start.
#include "connection/StreamThreads.h"

namespace vots::server {

bool StreamThreads::tryStart(std::function<void()> fn) {
    std::lock_guard lock(mMutex);
    reapLocked();
    if (mClosed || mRunning >= mMax) return false;
    Entry& entry = mEntries.emplace_back();
    ++mRunning;
    entry.thread = std::thread([this, &entry, fn = std::move(fn)] {
        fn();
        std::lock_guard done(mMutex);
        entry.finished = true; // the list node stays put (std::list) until reaped
        --mRunning;
    });
    return true;
}

void StreamThreads::reapLocked() {
    for (auto it = mEntries.begin(); it != mEntries.end();) {
        if (!it->finished) {
            ++it;
            continue;
        }
        it->thread.join(); // it has left fn and only returns now
        it = mEntries.erase(it);
    }
}

void StreamThreads::joinAll() {
    std::list<Entry> entries;
    {
        std::lock_guard lock(mMutex);
        mClosed = true;
        entries.splice(entries.begin(), mEntries);
    }
    for (Entry& entry : entries)
        entry.thread.join();
}

std::size_t StreamThreads::running() const {
    std::lock_guard lock(mMutex);
    return mRunning;
}

} // namespace vots::server
