// Fit jobs on worker threads: bounded queue, at most N running, one job per FitKey, progress for polling/SSE.
#pragma once

#include "vots/fit/Fitter.h"
#include "vots/server/DatasetRegistry.h"
#include "vots/server/FitKey.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {

class VotSpaceCache;
class ServerStats;

enum class JobState { Queued, Running, Done, Failed };
const char* jobStateName(JobState state); // "queued", "running", "done", "failed"

/// A copy of a job's visible state at one moment.
struct JobSnapshot {
    std::uint64_t id = 0;
    std::string key;
    std::string dataset;
    float eps = 0.f;
    int degree = 3;
    JobState state = JobState::Queued;
    double progress = 0.0; // 0..1
    std::string stage;     // fitter stage name ("split", "merge", "cache", ...)
    std::size_t votCount = 0;
    double fitSeconds = 0.0;
    std::string error;
    std::uint64_t version = 0; // bumps on every change (SSE sends when it moves)
};

/// One fit. Its Vot-Space is published once, when the state becomes Done.
class FitJob {
public:
    FitJob(std::uint64_t id, FitKey key);
    std::uint64_t id() const { return mId; }
    const FitKey& key() const { return mKey; }
    JobSnapshot snapshot() const;
    /// Waits until Done or Failed, or until timeout; returns the snapshot at that moment.
    JobSnapshot waitFinished(std::chrono::milliseconds timeout) const;
    /// Waits until the version moves past `seen` or the job finishes, at most timeout.
    JobSnapshot waitChange(std::uint64_t seen, std::chrono::milliseconds timeout) const;
    /// The result once Done, else null.
    std::shared_ptr<const fit::VotSpace> space() const;

    // Written by FitJobs only.
    void setRunning();
    void setProgress(double fraction, const char* stage);
    void finish(std::shared_ptr<const fit::VotSpace> space, double seconds);
    void fail(const std::string& error);

private:
    const std::uint64_t mId;
    const FitKey mKey;
    mutable std::mutex mMutex;
    mutable std::condition_variable mChanged;
    JobSnapshot mState;
    std::chrono::steady_clock::time_point mLastNotified{}; // last progress wake-up (setProgress)
    std::shared_ptr<const fit::VotSpace> mSpace;
};

struct FitJobLimits {
    int maxRunning = 2;    // fits at once
    int maxQueued = 8;     // waiting fits beyond those; more is refused with 429
    int keepFinished = 32; // finished jobs remembered for /api/jobs/{id}
    bool warmUp = true;    // fit eps / 2 into the box cache while idle (see FitJobs)
};

/// Background fits at half a finished fit's eps (warm-ups), for /api/stats.
struct WarmUpSummary {
    std::uint64_t started = 0, finished = 0, cancelled = 0, failed = 0;
    bool running = false;
    std::string lastKey; // the latest warm-up's FitKey text
    float lastEps = 0.f;
    double lastSeconds = 0.0;
};

/// Owns the worker threads. Thread-safe.
///
/// Warm-ups: a move of the eps slider to a smaller eps must fit boxes no earlier fit tried, which makes
/// it the slowest move. So when the last job has finished and nothing waits, one thread at nice 19
/// fits the dataset at half that eps (not below WARM_UP_FLOOR of its range) into the shared box cache;
/// a later refit anywhere between the two answers most boxes from the cache. Any new job cancels it.
/// Its Vot-Space is dropped: only the cache is wanted.
class FitJobs {
public:
    FitJobs(VotSpaceCache& cache, ServerStats& stats, FitJobLimits limits = {});
    ~FitJobs(); // shutdown(), then joins the workers
    FitJobs(const FitJobs&) = delete;
    FitJobs& operator=(const FitJobs&) = delete;

    /// Returns the job for this key: an active one, a finished one from the memory cache, or a new
    /// queued one. Throws HttpError 429 when the queue is full.
    std::shared_ptr<FitJob> submit(std::shared_ptr<const Dataset> dataset, const FitKey& key);
    /// Throws HttpError 404 for an unknown or forgotten id.
    std::shared_ptr<FitJob> find(std::uint64_t id) const;
    /// Queued plus running.
    int activeCount() const;
    WarmUpSummary warmUps() const;
    static constexpr float WARM_UP_FLOOR = 0.01f; // of the value range: a warm-up below it costs more
                                                  // (time, cache memory) than the rare move it helps
    /// Refuses new jobs (503), fails queued ones and cancels running fits; idempotent.
    void shutdown();

private:
    struct Pending {
        std::shared_ptr<FitJob> job;
        std::shared_ptr<const Dataset> dataset;
    };
    void workerLoop();
    void run(const Pending& pending);
    std::shared_ptr<fit::FitCache> fitCacheFor(const std::string& dataset, int degree);
    void rememberLocked(const std::shared_ptr<FitJob>& job);
    void startWarmUpLocked(const Pending& finished);
    void warmUp(std::shared_ptr<const Dataset> dataset, const FitKey& key);

    VotSpaceCache& mCache;
    ServerStats& mStats;
    const FitJobLimits mLimits;
    std::atomic<bool> mCancel{false};

    mutable std::mutex mMutex;
    std::condition_variable mWake;
    bool mStopping = false;
    std::deque<Pending> mQueue;
    int mRunning = 0;
    std::uint64_t mNextId = 1;
    std::map<std::string, std::shared_ptr<FitJob>> mActiveByKey; // queued or running
    std::map<std::uint64_t, std::shared_ptr<FitJob>> mById;      // active + recent finished
    std::deque<std::uint64_t> mFinishedOrder;
    std::map<std::string, std::shared_ptr<fit::FitCache>> mFitCaches; // "dataset/degree"
    std::vector<std::thread> mWorkers;

    std::atomic<bool> mWarmCancel{false};
    WarmUpSummary mWarm;           // under mMutex
    std::set<std::string> mWarmed; // warm-up keys already run (or running)
    std::thread mWarmThread;
};

} // namespace vots::server
