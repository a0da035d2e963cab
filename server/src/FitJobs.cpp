// FitJobs: a bounded queue of fits served by a fixed set of worker threads; results go to the cache.
#include "vots/server/FitJobs.h"

#include "LowPriorityQueue.h"

#include "vots/fit/Error.h"
#include "vots/server/HttpError.h"
#include "vots/server/ServerStats.h"
#include "vots/server/VotSpaceCache.h"

#include <algorithm>
#include <chrono>
#include <iostream>

namespace vots::server {
namespace {

constexpr std::size_t MAX_FIT_CACHES = 4; // per-(dataset, degree) box caches kept; each can grow large
constexpr std::size_t MAX_WARMED_KEYS = 4096;
constexpr auto WARM_UP_QUIET = std::chrono::milliseconds(250); // without frames before a warm-up goes on

fit::FitOptions optionsFor(const FitKey& key, int threads) {
    fit::FitOptions options;
    options.eps = key.eps;
    options.degree = key.degree;
    options.background = key.background;
    options.focus = key.focus;
    options.threads = threads;
    // Same rule as `vots render`: a MIP picks up overshoot between samples, so certify cells too.
    options.certify = fit::Certify::Cells;
    return options;
}

FitRecord recordFor(const JobSnapshot& job, const char* source) {
    return FitRecord{job.key, job.dataset, job.eps, job.degree, job.votCount, job.fitSeconds, source};
}

} // namespace

FitJobs::FitJobs(VotSpaceCache& cache, ServerStats& stats, FitJobLimits limits)
    : mCache(cache), mStats(stats), mLimits(limits) {
    for (int i = 0; i < std::max(1, mLimits.maxRunning); ++i)
        mWorkers.emplace_back([this] { workerLoop(); });
}

FitJobs::~FitJobs() {
    shutdown();
    for (std::thread& worker : mWorkers)
        worker.join();
    if (mWarmThread.joinable()) mWarmThread.join();
}

void FitJobs::shutdown() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
        for (const Pending& pending : mQueue)
            pending.job->fail("server is stopping");
        mQueue.clear();
    }
    mCancel = true; // running fits throw FitCancelled at their next check
    mWarmCancel = true;
    mWake.notify_all();
}

std::shared_ptr<FitJob> FitJobs::submit(std::shared_ptr<const Dataset> dataset, const FitKey& key) {
    const std::string text = key.text();
    {
        std::lock_guard lock(mMutex);
        if (mStopping) throw HttpError(503, "server is stopping");
        if (const auto it = mActiveByKey.find(text); it != mActiveByKey.end()) return it->second;
    }
    // Checked here so a bad focus is a 400 for the POST rather than a failed job later.
    fit::validateFitOptions(*dataset->volume, optionsFor(key, 0));

    std::lock_guard lock(mMutex);
    if (const auto it = mActiveByKey.find(text); it != mActiveByKey.end()) return it->second; // raced
    if (auto space = mCache.findInMemory(key)) {
        auto job = std::make_shared<FitJob>(mNextId++, key);
        const double seconds = VotSpaceCache::fitSecondsOf(*space);
        job->finish(std::move(space), seconds);
        mById[job->id()] = job;
        rememberLocked(job);
        return job;
    }
    if (static_cast<int>(mQueue.size()) + mRunning >= mLimits.maxRunning + mLimits.maxQueued)
        throw HttpError(429, "too many fit jobs; try again when one has finished");
    auto job = std::make_shared<FitJob>(mNextId++, key);
    mWarmCancel = true; // somebody waits for this one: a warm-up gives way
    mQueue.push_back(Pending{job, std::move(dataset)});
    mActiveByKey[text] = job;
    mById[job->id()] = job;
    mWake.notify_one();
    return job;
}

std::shared_ptr<FitJob> FitJobs::find(std::uint64_t id) const {
    std::lock_guard lock(mMutex);
    const auto it = mById.find(id);
    if (it == mById.end()) throw HttpError(404, "unknown job " + std::to_string(id));
    return it->second;
}

int FitJobs::activeCount() const {
    std::lock_guard lock(mMutex);
    return static_cast<int>(mQueue.size()) + mRunning;
}

void FitJobs::rememberLocked(const std::shared_ptr<FitJob>& job) {
    mFinishedOrder.push_back(job->id());
    while (mFinishedOrder.size() > static_cast<std::size_t>(std::max(1, mLimits.keepFinished))) {
        mById.erase(mFinishedOrder.front());
        mFinishedOrder.pop_front();
    }
}

std::shared_ptr<fit::FitCache> FitJobs::fitCacheFor(const std::string& dataset, int degree) {
    const std::string name = dataset + "/" + std::to_string(degree);
    std::lock_guard lock(mMutex);
    auto& slot = mFitCaches[name];
    if (!slot) {
        slot = std::make_shared<fit::FitCache>();
        if (mFitCaches.size() > MAX_FIT_CACHES) // drop another one; a running fit keeps its own alive
            mFitCaches.erase(mFitCaches.begin()->first == name ? std::next(mFitCaches.begin())
                                                               : mFitCaches.begin());
    }
    return slot;
}

void FitJobs::workerLoop() {
    for (;;) {
        Pending pending;
        {
            std::unique_lock lock(mMutex);
            mWake.wait(lock, [this] { return mStopping || !mQueue.empty(); });
            if (mStopping) return;
            pending = std::move(mQueue.front());
            mQueue.pop_front();
            ++mRunning;
        }
        run(pending);
        std::lock_guard lock(mMutex);
        --mRunning;
        mActiveByKey.erase(pending.job->key().text());
        rememberLocked(pending.job);
        if (pending.job->snapshot().state == JobState::Done) startWarmUpLocked(pending);
    }
}

WarmUpSummary FitJobs::warmUps() const {
    std::lock_guard lock(mMutex);
    return mWarm;
}

void FitJobs::startWarmUpLocked(const Pending& finished) {
    const FitKey& done = finished.job->key();
    if (!mLimits.warmUp || mStopping || mRunning > 0 || !mQueue.empty() || mWarm.running || done.focus)
        return;
    const std::array<float, 2> range = finished.dataset->range;
    FitKey key = done;
    key.eps = done.eps / 2.f;
    if (!(key.eps >= WARM_UP_FLOOR * (range[1] - range[0]))) return;
    if (mWarmed.size() >= MAX_WARMED_KEYS || !mWarmed.insert(key.text()).second) return;
    if (mWarmThread.joinable()) mWarmThread.join(); // the last one has ended: it cleared mWarm.running
    mWarm.running = true;
    ++mWarm.started;
    mWarm.lastKey = key.text();
    mWarm.lastEps = key.eps;
    mWarmCancel = false;
    mWarmThread = std::thread([this, dataset = finished.dataset, key] { warmUp(dataset, key); });
}

void FitJobs::warmUp(std::shared_ptr<const Dataset> dataset, const FitKey& key) {
    // Lowest priority, inherited by the fit's worker threads: it must not slow a frame or a fit. Nice 19
    // rather than SCHED_IDLE, which a busy machine could starve for minutes (~1.5 % vs ~0.3 % of a core).
    lowerThisThreadToNice19();
    const auto t0 = std::chrono::steady_clock::now();
    enum class End { Finished, Cancelled, Failed } end = End::Finished;
    try {
        fit::FitOptions options = optionsFor(key, 0);
        options.cancel = &mWarmCancel;
        // Called after each brick: there the warm-up waits while frames are being drawn. Running beside an
        // orbiting viewer, even at nice 19, it made frames ~15 % slower (cores, caches, memory bus).
        options.progress = [this](double, const char*) {
            while (!mWarmCancel && mStats.renderedWithin(WARM_UP_QUIET))
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
        };
        const auto boxCache = fitCacheFor(key.dataset, key.degree);
        fit::fitVotSpace(*dataset->volume, options, boxCache.get());
    } catch (const fit::FitCancelled&) {
        end = End::Cancelled;
    } catch (const std::exception& e) { // out of memory, say: the cache keeps what it got
        std::cerr << "vots serve: warm-up fit " << key.text() << " failed: " << e.what() << "\n";
        end = End::Failed;
    }
    std::lock_guard lock(mMutex);
    mWarm.lastSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++(end == End::Finished ? mWarm.finished : end == End::Cancelled ? mWarm.cancelled : mWarm.failed);
    if (end == End::Cancelled) mWarmed.erase(key.text()); // may run again later, from where it got to
    mWarm.running = false;
}

void FitJobs::run(const Pending& pending) {
    FitJob& job = *pending.job;
    const FitKey& key = job.key();
    const ForegroundMark mark(mStats, Foreground::Fit); // cache files of earlier fits wait meanwhile
    job.setRunning();
    try {
        if (auto space = mCache.find(key)) { // fitted by an earlier run of the server
            const double seconds = VotSpaceCache::fitSecondsOf(*space);
            job.finish(std::move(space), seconds);
            mStats.addFit(recordFor(job.snapshot(), "disk"));
            return;
        }
        // Every core per fit: the interactive case is one refit at a time, and a user waits for it.
        fit::FitOptions options = optionsFor(key, 0);
        options.progress = [&job](double fraction, const char* stage) { job.setProgress(fraction, stage); };
        options.cancel = &mCancel;
        // The box cache answers only uniform eps exactly; focus fits run without it.
        const auto boxCache = key.focus ? nullptr : fitCacheFor(key.dataset, key.degree);
        fit::FitResult result = fit::fitVotSpace(*pending.dataset->volume, options, boxCache.get());
        result.space.metaJson = VotSpaceCache::metaFor(key, result.stats.seconds);
        auto space = std::make_shared<const fit::VotSpace>(std::move(result.space));
        mCache.storeInMemory(key, space);
        job.finish(space, result.stats.seconds);
        mStats.addFit(recordFor(job.snapshot(), "fit"));
        mCache.storeOnDiskLater(key, space); // after the announcement: a waiting viewer needs only memory
    } catch (const fit::FitCancelled&) {
        job.fail("fit cancelled: the server is stopping");
    } catch (const std::bad_alloc&) {
        job.fail("out of memory while fitting");
    } catch (const std::exception& e) {
        std::cerr << "vots serve: fit " << key.text() << " failed: " << e.what() << "\n";
        job.fail(e.what());
    }
}

} // namespace vots::server
