// Cache files written later on a nice-19 thread, in the pauses of the foreground work a viewer waits for.
#pragma once

#include "fits/FitKey.h"

#include "vots/fit/VotSpace.h"

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>

namespace vots::server {

class LowPriorityQueue;
class VotSpaceStore;

/// Thread-safe. Encoding and syncing a large Vot-Space takes a core for a while: it must not slow the
/// frame a viewer waits for. A Vot-Space waiting for its write stays in memory even after the memory
/// cache has evicted it, so the writer bounds what it holds by bytes as well as by count: a burst of
/// fits of a large study would otherwise hold several GB outside every budget.
class DeferredDiskWriter {
public:
    /// Writes more than this many behind are skipped (with a warning).
    static constexpr std::size_t MAX_PENDING = 8;

    /// maxPendingBytes: a write that would make the Vot-Spaces waiting (or being written) exceed it is
    /// skipped with a warning, unless none waits (a single Vot-Space larger than it is still written).
    DeferredDiskWriter(VotSpaceStore& store, std::size_t maxPendingBytes);
    ~DeferredDiskWriter(); // finishes the queued writes, without waiting for quiet
    DeferredDiskWriter(const DeferredDiskWriter&) = delete;
    DeferredDiskWriter& operator=(const DeferredDiskWriter&) = delete;

    /// Queues the write of one file.
    void post(const FitKey& key, std::shared_ptr<const fit::VotSpace> space);
    /// Makes the writes give way to foreground work: a write starts no sooner than START_DELAY after it
    /// was queued (the viewer that waited for the fit asks for its frame then), and neither starts nor
    /// goes on to its next MiB while `busy()` is true, for at most MAX_DEFERRAL in all. Even at nice 19
    /// a write takes a core from the first frame of the new Vot-Space.
    void deferWhile(std::function<bool()> busy);
    /// Waits for the writes queued so far, deferred ones included (they start at once).
    void flush();
    /// Bytes (VotSpaceLru::bytesOf) of the Vot-Spaces queued or being written.
    std::size_t pendingBytes() const;

    static constexpr auto START_DELAY = std::chrono::milliseconds(300);
    static constexpr auto MAX_DEFERRAL = std::chrono::seconds(60);

private:
    /// Returns once busy() is false (and, with `startDelay`, START_DELAY after `queued`), or when
    /// waiting must end: a flush, or MAX_DEFERRAL after `queued`.
    void waitForQuiet(std::chrono::steady_clock::time_point queued, bool startDelay) const;

    VotSpaceStore& mStore;
    const std::size_t mMaxPendingBytes;
    mutable std::mutex mMutex;
    std::function<bool()> mBusy;              // deferWhile's test; guarded by mMutex
    std::size_t mPendingBytes = 0;            // guarded by mMutex
    std::atomic<int> mFlushRequests{0};       // > 0: deferred writes start at once
    std::unique_ptr<LowPriorityQueue> mQueue; // last: destroyed first, while the rest still exists
};

} // namespace vots::server
