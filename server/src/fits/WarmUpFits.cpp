// WarmUpFits: one low-priority thread that fits eps around the last one into the box cache, giving way to
// frames.
#include "fits/WarmUpFits.h"

#include "fits/BoxCaches.h"
#include "frames/ForegroundActivity.h"

#include "vots/fit/Error.h"
#include "vots/server/ThreadPriority.h"

#include <chrono>
#include <iostream>

namespace vots::server {
namespace {

constexpr std::size_t MAX_WARMED_KEYS = 4096;
// Without frames (and, before a warm-up starts, without a requested fit) for this long before a warm-up goes
// on.
constexpr auto QUIET = std::chrono::milliseconds(250);

} // namespace

WarmUpFits::WarmUpFits(BoxCaches& boxCaches, const ForegroundActivity& foreground, bool enabled)
    : mBoxCaches(boxCaches), mForeground(foreground), mEnabled(enabled) {}

WarmUpFits::~WarmUpFits() {
    stop();
    if (mThread.joinable()) mThread.join();
}

void WarmUpFits::stop() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
    }
    mCancel = true;
}

void WarmUpFits::giveWay() {
    mCancel = true;
}

WarmUpSummary WarmUpFits::summary() const {
    std::lock_guard lock(mMutex);
    return mSummary;
}

void WarmUpFits::afterIdleFit(std::shared_ptr<const Dataset> dataset, const FitKey& done) {
    std::lock_guard lock(mMutex);
    if (!mEnabled || mStopping || mSummary.running || done.focus) return;
    std::vector<FitKey> keys;
    for (const float factor : FACTORS) {
        FitKey key = done;
        key.eps = done.eps * factor;
        if (!(key.eps >= FLOOR * (dataset->range[1] - dataset->range[0]))) continue;
        if (mWarmed.size() >= MAX_WARMED_KEYS || !mWarmed.insert(key.text()).second) continue;
        keys.push_back(key);
    }
    if (keys.empty()) return;
    if (mThread.joinable()) mThread.join(); // the last one has ended: it cleared mSummary.running
    mSummary.running = true;
    mCancel = false;
    mThread = std::thread([this, dataset = std::move(dataset), keys] { run(dataset, keys); });
}

void WarmUpFits::run(std::shared_ptr<const Dataset> dataset, const std::vector<FitKey>& keys) {
    // Lowest priority, inherited by the fit's worker threads: it must not slow a frame or a fit. Nice 19
    // rather than SCHED_IDLE, which a busy machine can starve for minutes.
    lowerThisThreadToNice19();
    std::size_t done = 0; // keys finished, or failed
    for (; done < keys.size(); ++done) {
        const FitKey& key = keys[done];
        // Not while the fit that asked for these is still being shown: its upload and first frames follow
        // it at once, and a warm-up beside them, even at nice 19, delays the image the user waits for.
        while (!mCancel && mForeground.busyWithin(QUIET))
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        {
            std::lock_guard lock(mMutex);
            if (mCancel) break; // given way before this one started
            ++mSummary.started;
            mSummary.lastKey = key.text();
            mSummary.lastEps = key.eps;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const End end = fitOne(*dataset, key);
        std::lock_guard lock(mMutex);
        mSummary.lastSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++(end == End::Finished    ? mSummary.finished
           : end == End::Cancelled ? mSummary.cancelled
                                   : mSummary.failed);
        if (end == End::Failed) ++done;
        if (end != End::Finished) break;
    }
    std::lock_guard lock(mMutex);
    for (std::size_t rest = done; rest < keys.size(); ++rest)
        mWarmed.erase(keys[rest].text());
    mSummary.running = false;
}

WarmUpFits::End WarmUpFits::fitOne(const Dataset& dataset, const FitKey& key) {
    try {
        fit::FitOptions options = fitOptionsFor(key);
        options.cancel = &mCancel;
        // Called after each brick: there the warm-up waits while frames are being drawn. Even at nice 19
        // it slows the frames of an orbiting viewer (cores, caches, memory bus).
        options.progress = [this](double, const char*) {
            while (!mCancel && mForeground.renderedWithin(QUIET))
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
        };
        const auto boxCache = mBoxCaches.forFits(key.dataset, key.frame, key.degree);
        fit::fitVotSpace(*dataset.volume, options, boxCache.get());
        return End::Finished;
    } catch (const fit::FitCancelled&) {
        return End::Cancelled;
    } catch (const std::exception& e) { // out of memory, say: the cache keeps what it got
        std::cerr << "vots serve: warm-up fit " << key.text() << " failed: " << e.what() << "\n";
        return End::Failed;
    }
}

} // namespace vots::server
