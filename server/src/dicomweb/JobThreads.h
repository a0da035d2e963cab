// The thread-per-job bookkeeping the PACS opens and sends share: how a job ends, forgetting finished jobs,
// joining at the end.
#pragma once

#include "HttpError.h"
#include "dicomweb/PacsFailure.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

namespace vots::server {

/// Jobs by id; each Job has a `std::thread thread`.
template <class Job> using JobsById = std::map<std::uint64_t, std::unique_ptr<Job>>;

/// The job `id`, or HttpError 404 "unknown <what> <id>" for an unknown or forgotten one. Call under the
/// jobs' lock.
template <class Job>
Job& findJobLocked(const JobsById<Job>& jobs, std::uint64_t id, const std::string& what) {
    const auto it = jobs.find(id);
    if (it == jobs.end()) throw HttpError(404, "unknown " + what + " " + std::to_string(id));
    return *it->second;
}

/// Records `finishedId` as finished and forgets the oldest finished jobs beyond `keep`, joining their
/// threads: they ended right after their last update. Call under the jobs' lock, from the finishing job.
template <class Job>
void forgetFinishedJobs(JobsById<Job>& jobs, std::deque<std::uint64_t>& finished, std::uint64_t finishedId,
                        std::size_t keep) {
    finished.push_back(finishedId);
    while (finished.size() > keep) {
        const auto forgotten = jobs.find(finished.front());
        finished.pop_front();
        if (forgotten == jobs.end()) continue;
        forgotten->second->thread.join();
        jobs.erase(forgotten);
    }
}

/// How the job's thread ends, under `mutex`: a job that threw `failure` is Cancelled when `cancelled`, else
/// Failed with the HTTP status and message pacsFailure maps the failure to; then it is no longer running,
/// and the oldest finished jobs beyond `keep` are forgotten (forgetFinishedJobs). Call last in the thread.
template <class Job>
void endJob(std::mutex& mutex, JobsById<Job>& jobs, std::deque<std::uint64_t>& finished, int& running,
            Job& job, std::exception_ptr failure, bool cancelled, std::size_t keep) {
    using State = decltype(job.visible.state);
    const std::optional<HttpError> error =
        failure ? std::optional<HttpError>(pacsFailure(failure)) : std::nullopt;
    std::lock_guard lock(mutex);
    if (error) {
        job.visible.state = cancelled ? State::Cancelled : State::Failed;
        job.visible.errorStatus = cancelled ? 0 : error->status();
        job.visible.error = cancelled ? "cancelled" : error->what();
    }
    --running;
    forgetFinishedJobs(jobs, finished, job.visible.id, keep);
}

/// Sets every job's `stop` flag and joins every thread, outside the lock (a job's last update takes it).
template <class Job>
void stopAndJoinJobs(std::mutex& mutex, JobsById<Job>& jobs, std::atomic<bool> Job::*stop) {
    JobsById<Job> stopping;
    {
        std::lock_guard lock(mutex);
        for (auto& [id, job] : jobs)
            (*job).*stop = true;
        stopping.swap(jobs);
    }
    for (auto& [id, job] : stopping)
        if (job->thread.joinable()) job->thread.join();
}

} // namespace vots::server
