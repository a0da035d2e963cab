// SweepStoreJobs: the threads of the sends, their visible state, and the finished ones forgotten in turn.
#include "dicomweb/SweepStoreJobs.h"

#include "HttpError.h"
#include "dicomweb/JobThreads.h"

namespace vots::server {

SweepStoreJobs::~SweepStoreJobs() {
    stopAndJoinJobs(mMutex, mJobs, &Job::stop);
}

SweepStoreSnapshot SweepStoreJobs::start(SweepStoreSnapshot initial, Work work) {
    std::lock_guard lock(mMutex);
    if (mRunning >= MAX_RUNNING)
        throw HttpError(429,
                        std::to_string(MAX_RUNNING) + " sweeps are being sent; try again when one is in");
    auto job = std::make_unique<Job>();
    job->visible = std::move(initial);
    job->visible.id = mNextId++;
    job->visible.state = SweepStoreState::Queued;
    Job& started = *job;
    mJobs.emplace(started.visible.id, std::move(job));
    ++mRunning;
    started.thread = std::thread([this, &started, work = std::move(work)] { run(started, work); });
    return started.visible;
}

void SweepStoreJobs::run(Job& job, const Work& work) {
    const Update update = [this, &job](const std::function<void(SweepStoreSnapshot&)>& change) {
        std::lock_guard lock(mMutex);
        change(job.visible);
    };
    std::exception_ptr failure;
    try {
        work(update, job.stop);
        update([](SweepStoreSnapshot& s) { s.state = SweepStoreState::Done; });
    } catch (...) {
        failure = std::current_exception();
    }
    endJob(mMutex, mJobs, mFinished, mRunning, job, failure, job.cancelled.load(), KEEP_FINISHED);
}

SweepStoreSnapshot SweepStoreJobs::snapshot(std::uint64_t id) const {
    std::lock_guard lock(mMutex);
    return findJobLocked(mJobs, id, "sweep store").visible;
}

SweepStoreSnapshot SweepStoreJobs::cancel(std::uint64_t id) {
    std::lock_guard lock(mMutex);
    Job& job = findJobLocked(mJobs, id, "sweep store");
    if (!job.visible.ended()) {
        job.cancelled = true;
        job.stop = true;
    }
    return job.visible;
}

} // namespace vots::server
