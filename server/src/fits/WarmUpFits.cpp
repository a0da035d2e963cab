// WarmUpFits: one low-priority thread that fits the slider's rungs around the last eps ahead, giving way to
// frames.
#include "fits/WarmUpFits.h"

#include "fits/BoxCaches.h"
#include "fits/CacheMeta.h"
#include "fits/EpsLadder.h"
#include "fits/VotSpaceCache.h"
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

WarmUpFits::WarmUpFits(BoxCaches& boxCaches, VotSpaceCache& spaces, const ForegroundActivity& foreground,
                       bool enabled)
    : mBoxCaches(boxCaches), mSpaces(spaces), mForeground(foreground), mEnabled(enabled) {}

WarmUpFits::~WarmUpFits() {
    stop();
    if (mThread.joinable()) mThread.join();
}

void WarmUpFits::stop() {
    std::lock_guard lock(mMutex);
    mStopping = true;
    mDropPending = true;
    mCancel = true;
}

void WarmUpFits::giveWay() {
    std::lock_guard lock(mMutex);
    mDropPending = true;
    mCancel = true;
}

WarmUpSummary WarmUpFits::summary() const {
    std::lock_guard lock(mMutex);
    return mSummary;
}

void WarmUpFits::afterIdleFit(std::shared_ptr<const Dataset> dataset, const FitKey& done) {
    std::lock_guard lock(mMutex);
    if (!mEnabled || mStopping || done.focus) return;
    dropPendingLocked();
    std::vector<FitKey> keys;
    const std::vector<double> ladder = epsLadder(*dataset);
    // The drafts' rung first: every drag after this fit draws from it, a slider move only now and then.
    std::vector<double> rungs = rungsAround(ladder, done.eps, RUNGS);
    if (const auto draft = draftRung(ladder, done.eps, dataset->range[1] - dataset->range[0]))
        rungs.insert(rungs.begin(), *draft);
    for (const double rung : rungs) {
        FitKey key = done;
        key.eps = static_cast<float>(rung);
        if (!(key.eps >= FLOOR * (dataset->range[1] - dataset->range[0]))) continue;
        if (mWarmed.size() >= MAX_WARMED_KEYS || !mWarmed.insert(key.text()).second) continue;
        keys.push_back(key);
    }
    if (keys.empty()) return;
    mDataset = std::move(dataset);
    mPending = std::move(keys);
    // These replace what giveWay dropped. A warm-up it cancelled stays cancelled: the requested fit may end
    // before that one's fitter has looked at the flag (a fit at a large eps takes milliseconds).
    mDropPending = false;
    if (mSummary.running) return;
    if (mThread.joinable()) mThread.join(); // the last one has ended: it cleared mSummary.running
    mSummary.running = true;
    mThread = std::thread([this] { run(); });
}

void WarmUpFits::dropPendingLocked() {
    for (const FitKey& key : mPending)
        mWarmed.erase(key.text());
    mPending.clear();
}

void WarmUpFits::run() {
    // Lowest priority, inherited by the fit's worker threads: it must not slow a frame or a fit. Nice 19
    // rather than SCHED_IDLE, which a busy machine can starve for minutes.
    lowerThisThreadToNice19();
    // Whether pending keys are left; drops them first when a requested fit came (giveWay) since.
    const auto anyLeftLocked = [this] {
        if (mDropPending) dropPendingLocked();
        mDropPending = false;
        if (!mPending.empty()) return true;
        mDataset.reset();         // a dataset the registry drops (a 4D frame) is not kept alive here
        mSummary.running = false; // under the lock: afterIdleFit then starts a new thread
        return false;
    };
    for (;;) {
        {
            std::lock_guard lock(mMutex);
            if (!anyLeftLocked()) return;
            mCancel = false; // what stopped the last warm-up is dealt with; giveWay sets it again
        }
        // Not while the fit that asked for these is still being shown: its upload and first frames follow
        // it at once, and a warm-up beside them, even at nice 19, delays the image the user waits for.
        while (!mCancel && mForeground.busyWithin(QUIET))
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        FitKey key;
        std::shared_ptr<const Dataset> dataset;
        {
            std::lock_guard lock(mMutex);
            if (!anyLeftLocked()) return;
            key = mPending.front();
            mPending.erase(mPending.begin());
            dataset = mDataset;
        }
        // A requested fit, or a cache file of an earlier run (read into memory here), needs no warm-up.
        if (inFitCache(key)) continue;
        {
            std::lock_guard lock(mMutex);
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
        if (end == End::Cancelled) mWarmed.erase(key.text());
    }
}

bool WarmUpFits::inFitCache(const FitKey& key) {
    try {
        return mSpaces.find(key) != nullptr;
    } catch (const std::exception&) { // an unreadable cache file: the warm-up writes a new one
        return false;
    }
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
        fit::FitResult result = fit::fitVotSpace(*dataset.volume, options, boxCache.get());
        result.space.metaJson = cacheMetaFor(key, dataset, result.stats, result.space);
        auto space = std::make_shared<const fit::VotSpace>(std::move(result.space));
        // Memory only: ten warm-ups at a time would fill the disk writer's queue, and a cache file is for a
        // fit somebody asked for.
        mSpaces.storeInMemory(key, std::move(space));
        return End::Finished;
    } catch (const fit::FitCancelled&) {
        return End::Cancelled;
    } catch (const std::exception& e) { // out of memory, say: the cache keeps what it got
        std::cerr << "vots serve: warm-up fit " << key.text() << " failed: " << e.what() << "\n";
        return End::Failed;
    }
}

} // namespace vots::server
