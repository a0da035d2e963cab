// One fit's visible state (state, progress, result) with waits for "finished" and "changed".
#pragma once

#include "vots/fit/EnumNames.h"

#include "fits/FitKey.h"

#include "vots/fit/VotSpace.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

namespace vots::server {

enum class JobState { Queued, Running, Done, Failed };
inline constexpr auto JOB_STATE_NAMES = fit::nameTable<JobState>("job state", {{JobState::Queued, "queued"},
                                                                               {JobState::Running, "running"},
                                                                               {JobState::Done, "done"},
                                                                               {JobState::Failed, "failed"}});
constexpr const auto& namesOf(JobState) {
    return JOB_STATE_NAMES;
}

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
    /// The result once Done, else null; also null after releaseResult() once the memory cache has
    /// dropped it.
    std::shared_ptr<const fit::VotSpace> space() const;
    /// Keeps only a weak reference to the result: a remembered job must not hold a Vot-Space outside
    /// the memory cache's budget (32 remembered embryo fits held 9 GB in the soak).
    void releaseResult();

    // Written by the FitJobs workers only.
    void setRunning();
    void setProgress(double fraction, const char* stage);
    void finish(std::shared_ptr<const fit::VotSpace> space, double seconds);
    /// Done, with the Vot-Space held by other processes (`vots serve` under mpirun): space() stays null.
    void finishOnRanks(std::size_t votCount, double seconds);
    void fail(const std::string& error);

    /// Asks the job's fit to stop at its next check (fit::FitCancelled); one that starts later stops at its
    /// first. Thread-safe.
    void cancel() { mCancel.store(true, std::memory_order_relaxed); }
    /// What fit::FitOptions::cancel points at for this job's fit.
    const std::atomic<bool>* cancelFlag() const { return &mCancel; }

private:
    const std::uint64_t mId;
    const FitKey mKey;
    mutable std::mutex mMutex;
    mutable std::condition_variable mChanged;
    JobSnapshot mState;
    std::chrono::steady_clock::time_point mLastNotified{}; // last progress wake-up (setProgress)
    std::shared_ptr<const fit::VotSpace> mSpace;
    std::weak_ptr<const fit::VotSpace> mReleasedSpace; // after releaseResult()
    std::atomic<bool> mCancel{false};
};

} // namespace vots::server
