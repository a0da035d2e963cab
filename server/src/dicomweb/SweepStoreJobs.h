// Sending a slab sweep to a PACS: a job per send that draws the slabs on the render thread and stores them.
#pragma once

#include "vots/fit/EnumNames.h"

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace vots::server {

/// The steps of a send, in order, and how it ended.
enum class SweepStoreState { Queued, Drawing, Storing, Done, Failed, Cancelled };
inline constexpr auto SWEEP_STORE_STATE_NAMES =
    fit::nameTable<SweepStoreState>("sweep store state", {{SweepStoreState::Queued, "queued"},
                                                          {SweepStoreState::Drawing, "drawing"},
                                                          {SweepStoreState::Storing, "storing"},
                                                          {SweepStoreState::Done, "done"},
                                                          {SweepStoreState::Failed, "failed"},
                                                          {SweepStoreState::Cancelled, "cancelled"}});
constexpr const auto& namesOf(SweepStoreState) {
    return SWEEP_STORE_STATE_NAMES;
}

/// What GET /api/pacs/stores/{id} reports.
struct SweepStoreSnapshot {
    std::uint64_t id = 0;
    std::string service;
    std::string dataset;
    std::string description; // the series' SeriesDescription, e.g. "MIP 10 mm / 5 mm axial"
    SweepStoreState state = SweepStoreState::Queued;
    int drawn = 0;       // slabs drawn so far
    int total = 0;       // slabs of the sweep
    int stored = 0;      // done: the images the PACS says it stored
    int errorStatus = 0; // failed: the HTTP status the failure maps to (pacsFailure)
    std::string error;

    bool ended() const { return state >= SweepStoreState::Done; }
};

/// Thread-safe. Each send runs on a thread of its own, at most MAX_RUNNING at once (429 beyond); its
/// frames queue on the render thread one at a time, between other clients' frames.
class SweepStoreJobs {
public:
    static constexpr int MAX_RUNNING = 2;
    static constexpr std::size_t KEEP_FINISHED = 32;

    /// Changes a send's visible state (under the jobs' lock).
    using Update = std::function<void(const std::function<void(SweepStoreSnapshot&)>&)>;
    /// The send's work: draws, writes and stores, telling its progress through `update`; stops with an
    /// exception when `stop` is set. What it throws ends the send as failed, with pacsFailure's status.
    using Work = std::function<void(const Update& update, const std::atomic<bool>& stop)>;

    SweepStoreJobs() = default;
    ~SweepStoreJobs(); // stops every send and joins the threads
    SweepStoreJobs(const SweepStoreJobs&) = delete;
    SweepStoreJobs& operator=(const SweepStoreJobs&) = delete;

    /// Starts a send described by `initial` (its id is given here); HttpError 429 when too many run.
    SweepStoreSnapshot start(SweepStoreSnapshot initial, Work work);
    /// HttpError 404 for an unknown or forgotten id.
    SweepStoreSnapshot snapshot(std::uint64_t id) const;
    /// Stops a send: between slabs while drawing, the request in flight while storing (nothing is
    /// stored then, as STOW-RS stores a request's instances only once it has them all). It ends
    /// cancelled, unless it ended first. HttpError 404 as snapshot.
    SweepStoreSnapshot cancel(std::uint64_t id);

private:
    struct Job {
        SweepStoreSnapshot visible; // written under mMutex
        std::atomic<bool> stop{false};
        std::atomic<bool> cancelled{false}; // stopped by cancel(), not by the server's end
        std::thread thread;
    };
    void run(Job& job, const Work& work);

    mutable std::mutex mMutex;
    std::uint64_t mNextId = 1;
    int mRunning = 0;
    std::map<std::uint64_t, std::unique_ptr<Job>> mJobs;
    std::deque<std::uint64_t> mFinished; // oldest first; forgotten beyond KEEP_FINISHED
};

} // namespace vots::server
