// DeferredDiskWriter: a LowPriorityQueue of store writes, each waiting for a quiet moment first.
#include "fits/DeferredDiskWriter.h"

#include "fits/LowPriorityQueue.h"
#include "fits/VotSpaceLru.h"
#include "fits/VotSpaceStore.h"

#include <iostream>
#include <thread>

namespace vots::server {

DeferredDiskWriter::DeferredDiskWriter(VotSpaceStore& store, std::size_t maxPendingBytes)
    : mStore(store), mMaxPendingBytes(maxPendingBytes),
      mQueue(std::make_unique<LowPriorityQueue>(MAX_PENDING)) {}

DeferredDiskWriter::~DeferredDiskWriter() {
    ++mFlushRequests; // the queue, destroyed first, finishes its tasks without waiting for quiet
}

void DeferredDiskWriter::deferWhile(std::function<bool()> busy) {
    std::lock_guard lock(mMutex);
    mBusy = std::move(busy);
}

void DeferredDiskWriter::waitForQuiet(std::chrono::steady_clock::time_point queued, bool startDelay) const {
    std::function<bool()> busy;
    {
        std::lock_guard lock(mMutex);
        busy = mBusy;
    }
    if (!busy) return;
    for (;;) {
        const auto now = std::chrono::steady_clock::now();
        if (mFlushRequests > 0 || now >= queued + MAX_DEFERRAL) return;
        if ((!startDelay || now >= queued + START_DELAY) && !busy()) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

void DeferredDiskWriter::post(const FitKey& key, std::shared_ptr<const fit::VotSpace> space) {
    const auto queued = std::chrono::steady_clock::now();
    const std::size_t bytes = VotSpaceLru::bytesOf(*space);
    {
        std::lock_guard lock(mMutex);
        if (mPendingBytes > 0 && mPendingBytes + bytes > mMaxPendingBytes) {
            std::cerr << "vots serve: warning: " << key.text()
                      << " is not written to the cache folder: the writes waiting hold "
                      << (mPendingBytes >> 20) << " MiB, the most they may is " << (mMaxPendingBytes >> 20)
                      << " MiB\n";
            return;
        }
        mPendingBytes += bytes;
    }
    const auto written = [this, bytes] {
        std::lock_guard lock(mMutex);
        mPendingBytes -= bytes;
    };
    if (!mQueue->post([this, key, space = std::move(space), queued, written] {
            waitForQuiet(queued, true);
            mStore.write(key, *space, [this, queued] { waitForQuiet(queued, false); });
            written();
        })) {
        written();
        std::cerr << "vots serve: warning: " << key.text()
                  << " is not written to the cache folder: the writer is " << MAX_PENDING
                  << " files behind\n";
    }
}

std::size_t DeferredDiskWriter::pendingBytes() const {
    std::lock_guard lock(mMutex);
    return mPendingBytes;
}

void DeferredDiskWriter::flush() {
    ++mFlushRequests;
    mQueue->drain();
    --mFlushRequests;
}

} // namespace vots::server
