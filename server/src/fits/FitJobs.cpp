// FitJobs: a bounded queue of fits served by a fixed set of worker threads; results go to the cache.
#include "fits/FitJobs.h"

#include "HttpError.h"
#include "ServerStats.h"
#include "fits/CacheMeta.h"
#include "fits/VotSpaceCache.h"
#include "frames/ForegroundActivity.h"

#include "vots/fit/Error.h"

#include <malloc.h>

#include <algorithm>
#include <iostream>

namespace vots::server {
namespace {

// The fitter's freed working memory goes back to the kernel: otherwise malloc keeps it in its arenas,
// where it still counts as resident and the memory budget (MemoryAdmission) would refuse the next fit.
void returnFreedMemory() {
#ifdef __GLIBC__
    ::malloc_trim(0);
#endif
}

FitRecord recordFor(const JobSnapshot& job, const char* source) {
    return FitRecord{job.key, job.dataset, job.eps, job.degree, job.votCount, job.fitSeconds, source};
}

} // namespace

FitJobs::FitJobs(VotSpaceCache& cache, ServerStats& stats, ForegroundActivity& foreground,
                 MemoryAdmission& memory, FitJobLimits limits)
    : mCache(cache), mStats(stats), mForeground(foreground), mMemory(memory), mLimits(limits),
      mPerClient(limits.perClient, "fits"), mBoxCaches(limits.boxCacheBytes),
      mWarmUps(mBoxCaches, cache, foreground, limits.warmUp) {
    for (int i = 0; i < std::max(1, mLimits.maxRunning); ++i)
        mWorkers.emplace_back([this] { workerLoop(); });
}

FitJobs::~FitJobs() {
    shutdown();
    for (std::thread& worker : mWorkers)
        worker.join();
}

void FitJobs::shutdown() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
        for (const Pending& pending : mQueue)
            pending.job->fail("server is stopping");
        mQueue.clear();
        for (const auto& [text, active] : mActiveByKey)
            active.job->cancel(); // running fits throw FitCancelled at their next check
    }
    mWarmUps.stop();
    mWake.notify_all();
}

std::shared_ptr<FitJob> FitJobs::submit(std::shared_ptr<const Dataset> dataset, const FitKey& key,
                                        const std::string& client, const std::string& viewer) {
    const std::string text = key.text();
    // Joins the active job for the key (the caller now wants it too), if there is one.
    const auto join = [&](Active& active) {
        if (viewer.empty()) {
            ++active.others;
        } else {
            active.viewers.insert(viewer);
            mViewerWants[viewer] = text;
        }
        return active.job;
    };
    {
        std::lock_guard lock(mMutex);
        if (mStopping) throw HttpError(503, "server is stopping");
        if (!viewer.empty()) withdrawLocked(viewer, text);
        if (const auto it = mActiveByKey.find(text); it != mActiveByKey.end()) return join(it->second);
    }
    // Checked here so a bad focus is a 400 for the POST rather than a failed job later; samples held by the
    // ranks are checked there, each rank's error failing the job.
    if (!dataset->samplesOnRanks) fit::validateFitOptions(*dataset->volume, fitOptionsFor(key));

    std::lock_guard lock(mMutex);
    if (const auto it = mActiveByKey.find(text); it != mActiveByKey.end()) return join(it->second); // raced
    if (auto space = mCache.findInMemory(key)) {
        auto job = std::make_shared<FitJob>(mNextId++, key);
        const double seconds = fitSecondsOf(*space);
        job->finish(std::move(space), seconds);
        mById[job->id()] = job;
        rememberLocked(job);
        warmUpAroundLocked(dataset, key); // the hand moved to a warmed eps: warm its next moves too
        return job;
    }
    if (static_cast<int>(mQueue.size()) + mRunning >= mLimits.maxRunning + mLimits.maxQueued)
        throw HttpError(429, "too many fit jobs; try again when one has finished");
    ClientQuota::Ticket clientPlace = client.empty() ? ClientQuota::Ticket() : mPerClient.enter(client);
    MemoryReservation memory = mMemory.admit(dataset->fitBytes, "a fit of dataset '" + key.dataset + "'");
    auto job = std::make_shared<FitJob>(mNextId++, key);
    mWarmUps.giveWay(); // somebody waits for this one
    mQueue.push_back(Pending{job, std::move(dataset), std::move(memory), std::move(clientPlace)});
    join(mActiveByKey[text] = Active{job, 0, {}});
    mById[job->id()] = job;
    mWake.notify_one();
    return job;
}

void FitJobs::withdrawLocked(const std::string& viewer, const std::string& wantedNow) {
    const auto wanted = mViewerWants.find(viewer);
    if (wanted == mViewerWants.end() || wanted->second == wantedNow) return;
    const auto active = mActiveByKey.find(wanted->second);
    mViewerWants.erase(wanted);
    if (active == mActiveByKey.end()) return;
    active->second.viewers.erase(viewer);
    if (active->second.others == 0 && active->second.viewers.empty()) cancelLocked(active);
}

void FitJobs::cancelLocked(std::map<std::string, Active>::iterator active) {
    const std::shared_ptr<FitJob> job = active->second.job;
    const auto queued =
        std::find_if(mQueue.begin(), mQueue.end(), [&](const Pending& p) { return p.job == job; });
    if (queued != mQueue.end()) {
        mQueue.erase(queued); // gives back its memory reservation and its client's place
        mActiveByKey.erase(active);
        job->fail(SUPERSEDED_FIT);
        rememberLocked(job);
        return;
    }
    // The ranks' fit cannot be stopped (each rank fits its cells to the end): it stays the active job for
    // its key, for whoever asks for it next, instead of a second fit of the same key beside it.
    if (mFitOnRanks) return;
    // Off the active jobs at once: a new request for the same key starts a new job instead of joining one
    // that is stopping.
    mActiveByKey.erase(active);
    job->cancel(); // its worker fails it when the fit stops
}

void FitJobs::endLocked(const std::shared_ptr<FitJob>& job) {
    const auto active = mActiveByKey.find(job->key().text());
    if (active == mActiveByKey.end() || active->second.job != job) return;
    for (const std::string& viewer : active->second.viewers)
        mViewerWants.erase(viewer); // each still wanted this job (a newer wish would have withdrawn it)
    mActiveByKey.erase(active);
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
    job->releaseResult(); // the memory cache holds it, within its budget
    mFinishedOrder.push_back(job->id());
    while (mFinishedOrder.size() > static_cast<std::size_t>(std::max(1, mLimits.keepFinished))) {
        mById.erase(mFinishedOrder.front());
        mFinishedOrder.pop_front();
    }
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
        returnFreedMemory();
        std::lock_guard lock(mMutex);
        --mRunning;
        endLocked(pending.job);
        rememberLocked(pending.job);
        if (pending.job->snapshot().state == JobState::Done && !mStopping)
            warmUpAroundLocked(pending.dataset, pending.job->key());
    }
}

void FitJobs::warmUpAroundLocked(const std::shared_ptr<const Dataset>& dataset, const FitKey& key) {
    // A requested fit makes a warm-up give way, so it holds no memory reservation and starts only with room.
    if (mRunning == 0 && mQueue.empty() && mMemory.available() >= dataset->fitBytes)
        mWarmUps.afterIdleFit(dataset, key);
}

void FitJobs::run(const Pending& pending) {
    FitJob& job = *pending.job;
    const FitKey& key = job.key();
    const ForegroundMark mark(mForeground, Foreground::Fit); // cache files of earlier fits wait meanwhile
    job.setRunning();
    try {
        if (mFitOnRanks) {
            const FitOnRanks done =
                mFitOnRanks(*pending.dataset, key,
                            [&job](double fraction, const char* stage) { job.setProgress(fraction, stage); });
            job.finishOnRanks(done.votCount, done.seconds);
            mStats.addFit(recordFor(job.snapshot(), "ranks"));
            return;
        }
        if (auto space = mCache.find(key)) { // fitted by an earlier run of the server
            if (mUploadFit) mUploadFit(*pending.dataset, space);
            const double seconds = fitSecondsOf(*space);
            job.finish(std::move(space), seconds);
            mStats.addFit(recordFor(job.snapshot(), "disk"));
            return;
        }
        // Every core per fit: the interactive case is one refit at a time, and a user waits for it.
        fit::FitOptions options = fitOptionsFor(key);
        options.progress = [&job](double fraction, const char* stage) { job.setProgress(fraction, stage); };
        options.cancel = job.cancelFlag();
        // The box cache answers only uniform eps exactly; focus fits run without it.
        const auto boxCache = key.focus ? nullptr : mBoxCaches.forFits(key.dataset, key.frame, key.degree);
        fit::FitResult result = fit::fitVotSpace(*pending.dataset->volume, options, boxCache.get());
        result.space.metaJson = cacheMetaFor(key, *pending.dataset, result.stats, result.space);
        auto space = std::make_shared<const fit::VotSpace>(std::move(result.space));
        mCache.storeInMemory(key, space);
        if (mUploadFit) mUploadFit(*pending.dataset, space);
        job.finish(space, result.stats.seconds);
        mStats.addFit(recordFor(job.snapshot(), "fit"));
        mCache.storeOnDiskLater(key, space); // after the announcement: a waiting viewer needs only memory
    } catch (const fit::FitCancelled&) {
        std::lock_guard lock(mMutex);
        job.fail(mStopping ? "fit cancelled: the server is stopping" : SUPERSEDED_FIT);
    } catch (const std::bad_alloc&) {
        job.fail("out of memory while fitting");
    } catch (const std::exception& e) {
        std::cerr << "vots serve: fit " << key.text() << " failed: " << e.what() << "\n";
        job.fail(e.what());
    }
}

} // namespace vots::server
