// Point-to-point MPI for `vots serve` under mpirun: byte messages, and waits polled against deadlines, so
// that a rank that has died is noticed instead of waited for; every call serialized by one lock.
#pragma once

#include <chrono>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include <mpi.h>

namespace vots::dist {

using PollClock = std::chrono::steady_clock;

/// MPI is initialised MPI_THREAD_SERIALIZED and rank 0 calls it from two threads (frames, heartbeats):
/// each call in this file's functions holds this lock, and so must any other call made while serving.
std::mutex& mpiCallLock();

/// Asked between polls: false ends a wait as its deadline does (a peer found silent for too long).
using KeepWaiting = std::function<bool()>;

/// Waits for a whole message from `source` until `deadline` (none: for ever) while `keepWaiting` (when
/// given) holds; nullopt when none came in time, its transfer did not end in time (a sender that died
/// mid-message), or MPI reports an error.
std::optional<std::vector<char>> receiveBefore(int source, int tag,
                                               std::optional<PollClock::time_point> deadline,
                                               const KeepWaiting& keepWaiting = {});

/// Completes a nonblocking request by `deadline` while `keepWaiting` (when given) holds; false when it did
/// not (the request is left to MPI).
bool completedBefore(MPI_Request& request, PollClock::time_point deadline,
                     const KeepWaiting& keepWaiting = {});

/// Takes every empty message with `tag` that has arrived, from any rank; returns their senders.
std::vector<int> takeArrived(int tag);

/// Starts sending `bytes` (which must outlive the send) to `dest`; false when MPI refuses.
bool startSend(const std::vector<char>& bytes, int dest, int tag, MPI_Request& request);

/// True when a send started by startSend has completed (or was never started).
bool sendDone(MPI_Request& request);

} // namespace vots::dist
