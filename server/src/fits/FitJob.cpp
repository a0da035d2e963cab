// FitJob: one fit's visible state behind a mutex, with waits for "finished" and "changed".
#include "fits/FitJob.h"

#include <algorithm>

namespace vots::server {

namespace {
constexpr auto PROGRESS_INTERVAL = std::chrono::milliseconds(100);

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
    return mSpace ? mSpace : mReleasedSpace.lock();
}

void FitJob::releaseResult() {
    std::lock_guard lock(mMutex);
    if (!mSpace) return;
    mReleasedSpace = mSpace;
    mSpace.reset();
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
    mState.progress = std::max(mState.progress, std::min(1.0, std::max(0.0, fraction))); // never goes back
    const std::string stageText = stage ? stage : "";
    // A fit reports every brick, thousands on a CT. Each wake-up reaches every SSE stream and, through
    // it, a browser redrawing its progress bar: on a machine with few cores that takes CPU from the fit
    // itself. Watchers
    // hear of each new stage at once and of progress at most PROGRESS_INTERVAL apart.
    const auto now = std::chrono::steady_clock::now();
    if (stageText == mState.stage && now - mLastNotified < PROGRESS_INTERVAL) return;
    mLastNotified = now;
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

void FitJob::finishOnRanks(std::size_t votCount, double seconds) {
    std::lock_guard lock(mMutex);
    mState.votCount = votCount;
    mState.fitSeconds = seconds;
    mState.progress = 1.0;
    mState.stage = "done";
    mState.state = JobState::Done;
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
