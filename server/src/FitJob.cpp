// FitJob: one fit's visible state behind a mutex, with waits for "finished" and "changed".
#include "vots/server/FitJobs.h"

#include <algorithm>
#include <cmath>

namespace vots::server {

const char* jobStateName(JobState state) {
    switch (state) {
    case JobState::Queued:
        return "queued";
    case JobState::Running:
        return "running";
    case JobState::Done:
        return "done";
    case JobState::Failed:
        return "failed";
    }
    return "unknown";
}

namespace {
bool isFinished(JobState state) {
    return state == JobState::Done || state == JobState::Failed;
}
} // namespace

FitJob::FitJob(std::uint64_t id, FitKey key) : mId(id), mKey(std::move(key)) {
    mState.id = id;
    mState.key = mKey.text();
    mState.dataset = mKey.dataset;
    mState.eps = mKey.eps;
    mState.degree = mKey.degree;
    mState.stage = "queued";
}

JobSnapshot FitJob::snapshot() const {
    std::lock_guard lock(mMutex);
    return mState;
}

JobSnapshot FitJob::waitFinished(std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mMutex);
    mChanged.wait_for(lock, timeout, [this] { return isFinished(mState.state); });
    return mState;
}

JobSnapshot FitJob::waitChange(std::uint64_t seen, std::chrono::milliseconds timeout) const {
    std::unique_lock lock(mMutex);
    mChanged.wait_for(lock, timeout,
                      [this, seen] { return mState.version != seen || isFinished(mState.state); });
    return mState;
}

std::shared_ptr<const fit::VotSpace> FitJob::space() const {
    std::lock_guard lock(mMutex);
    return mSpace;
}

void FitJob::setRunning() {
    std::lock_guard lock(mMutex);
    mState.state = JobState::Running;
    mState.stage = "starting";
    ++mState.version;
    mChanged.notify_all();
}

void FitJob::setProgress(double fraction, const char* stage) {
    std::lock_guard lock(mMutex);
    const double before = mState.progress;
    mState.progress = std::max(before, std::min(1.0, std::max(0.0, fraction))); // never goes back
    const std::string stageText = stage ? stage : "";
    // A fit reports every brick (~2,000 on the CT); waking every SSE stream for each cost the fit
    // itself CPU on a 2-core machine. Watchers hear of each new stage and of every whole percent.
    if (stageText == mState.stage && mState.progress < 1.0 &&
        std::floor(mState.progress * 100.0) == std::floor(before * 100.0))
        return;
    mState.stage = stageText;
    ++mState.version;
    mChanged.notify_all();
}

void FitJob::finish(std::shared_ptr<const fit::VotSpace> space, double seconds) {
    std::lock_guard lock(mMutex);
    mState.votCount = space->vots.size();
    mState.fitSeconds = seconds;
    mState.progress = 1.0;
    mState.stage = "done";
    mState.state = JobState::Done;
    mSpace = std::move(space);
    ++mState.version;
    mChanged.notify_all();
}

void FitJob::fail(const std::string& error) {
    std::lock_guard lock(mMutex);
    mState.error = error;
    mState.stage = "failed";
    mState.state = JobState::Failed;
    ++mState.version;
    mChanged.notify_all();
}

} // namespace vots::server
