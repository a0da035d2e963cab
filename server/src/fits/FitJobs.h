// Fit jobs on worker threads: bounded queue, at most N running, one job per FitKey, results to the cache.
#pragma once

#include "connection/ClientQuota.h"
#include "datasets/DatasetRegistry.h"
#include "datasets/MemoryAdmission.h"
#include "fits/BoxCaches.h"
#include "fits/FitJob.h"
#include "fits/FitKey.h"
#include "fits/WarmUpFits.h"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {

class ForegroundActivity;
class ServerStats;
class VotSpaceCache;

/// The error of a fit cancelled because the viewer that asked for it asked for another (FitJobs::submit).
inline constexpr const char* SUPERSEDED_FIT =
    "superseded: the viewer that asked for this fit asked for another";

struct FitJobLimits {
    int maxRunning = 2;    // fits at once
    int maxQueued = 8;     // waiting fits beyond those; more is refused with 429
    int perClient = 3;     // queued or running fits one client (remote address) started; 0: no limit
    int keepFinished = 32; // finished jobs remembered for /api/jobs/{id} (their results only weakly)
    bool warmUp = true;    // fit the slider's rungs around the last eps while idle (WarmUpFits)
    std::uint64_t boxCacheBytes = std::uint64_t{1} << 30; // the fitter's box caches (BoxCaches)
};

/// What a fit made by other processes gave (`vots serve` under mpirun): the Vots of all the ranks' cells
/// and the slowest rank's seconds. The Vot-Space itself stays with the ranks.
struct FitOnRanks {
    std::size_t votCount = 0;
    double seconds = 0.0;
};

/// Owns the worker threads and the warm-ups that follow their fits. Thread-safe.
class FitJobs {
public:
    FitJobs(VotSpaceCache& cache, ServerStats& stats, ForegroundActivity& foreground, MemoryAdmission& memory,
            FitJobLimits limits = {});
    ~FitJobs(); // shutdown(), then joins the workers
    FitJobs(const FitJobs&) = delete;
    FitJobs& operator=(const FitJobs&) = delete;

    /// Returns the job for this key: an active one, a finished one from the memory cache, or a new
    /// queued one. Throws HttpError 429 when the queue is full, 507 when the memory budget does not leave
    /// room for the fit (Dataset::fitBytes; reserved until the job ends). Warm-ups start only with room.
    /// A new job counts against its client's FitJobLimits::perClient until it ends (429 beyond); joining
    /// a job already active costs nothing. An empty client is not limited (the server's own fits).
    /// `viewer` names an interactive viewer (the caller scopes it, e.g. by address), which wants one fit
    /// at a time: asking for another withdraws it from the one it asked for before, and a job that no
    /// one wants any more is cancelled (failed with SUPERSEDED_FIT). A request without a viewer (a
    /// script, a /render waiting for its fit) always wants its job to the end.
    std::shared_ptr<FitJob> submit(std::shared_ptr<const Dataset> dataset, const FitKey& key,
                                   const std::string& client = {}, const std::string& viewer = {});
    /// Throws HttpError 404 for an unknown or forgotten id.
    std::shared_ptr<FitJob> find(std::uint64_t id) const;
    /// Queued plus running.
    int activeCount() const;
    WarmUpSummary warmUps() const { return mWarmUps.summary(); }
    BoxCacheStats boxCaches() const { return mBoxCaches.stats(); }
    /// Refuses new jobs (503), fails queued ones and cancels running fits; idempotent.
    void shutdown();
    /// Under mpirun: every fit is made by the ranks, each of its z cells, through `fit` (which waits for
    /// them), instead of here. Set before the first submit.
    void
    fitOnRanksThrough(std::function<FitOnRanks(const Dataset&, const FitKey&, const fit::FitProgress&)> fit) {
        mFitOnRanks = std::move(fit);
    }
    /// `upload` is given each Vot-Space a requested fit makes (or reads from the disk cache), on the fit's
    /// worker, before the job is announced done: the server has the renderer upload it meanwhile, so that
    /// the viewer's first frame at the new eps does not begin with the upload. Set before the first submit.
    void uploadFitsThrough(std::function<void(const Dataset&, std::shared_ptr<const fit::VotSpace>)> upload) {
        mUploadFit = std::move(upload);
    }

private:
    struct Pending {
        std::shared_ptr<FitJob> job;
        std::shared_ptr<const Dataset> dataset;
        MemoryReservation memory; // the fit's working memory, given back when the job ends
        ClientQuota::Ticket clientPlace;
    };
    /// A queued or running job and who wants it.
    struct Active {
        std::shared_ptr<FitJob> job;
        int others = 0;                // requests without a viewer: they never withdraw
        std::set<std::string> viewers; // viewers whose latest request it is
    };
    void workerLoop();
    void run(const Pending& pending);
    void rememberLocked(const std::shared_ptr<FitJob>& job);
    /// The viewer no longer wants the job it asked for last; that job is cancelled when nobody does.
    /// (Unless that job is `wantedNow`, the key text it asks for now.)
    void withdrawLocked(const std::string& viewer, const std::string& wantedNow);
    /// Takes a job nobody wants off the active ones: out of the queue and failed, or told to stop.
    void cancelLocked(std::map<std::string, Active>::iterator active);
    /// The job's entry, when it is the active one for its key; else it is already off (cancelled).
    void endLocked(const std::shared_ptr<FitJob>& job);
    /// The Vot-Space of `key` is ready (fitted, or found in the cache): its warm-ups start when no fit waits
    /// or runs and the memory budget has room for a fit (a warm-up holds no reservation).
    void warmUpAroundLocked(const std::shared_ptr<const Dataset>& dataset, const FitKey& key);

    VotSpaceCache& mCache;
    ServerStats& mStats;
    ForegroundActivity& mForeground;
    MemoryAdmission& mMemory;
    const FitJobLimits mLimits;
    ClientQuota mPerClient;
    BoxCaches mBoxCaches;
    WarmUpFits mWarmUps; // after mBoxCaches, which its thread uses until it is joined

    mutable std::mutex mMutex;
    std::condition_variable mWake;
    bool mStopping = false;
    std::deque<Pending> mQueue;
    int mRunning = 0;
    std::uint64_t mNextId = 1;
    std::map<std::string, Active> mActiveByKey;             // queued or running, by key text
    std::map<std::string, std::string> mViewerWants;        // viewer -> key text of its latest active job
    std::map<std::uint64_t, std::shared_ptr<FitJob>> mById; // active + recent finished
    std::deque<std::uint64_t> mFinishedOrder;
    std::vector<std::thread> mWorkers;
    std::function<FitOnRanks(const Dataset&, const FitKey&, const fit::FitProgress&)> mFitOnRanks;
    std::function<void(const Dataset&, std::shared_ptr<const fit::VotSpace>)> mUploadFit;
};

} // namespace vots::server
