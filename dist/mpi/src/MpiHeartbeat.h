// The other ranks' heartbeat to rank 0 under `vots serve` with mpirun: sent from a thread of their own, so
// that rank 0 tells a rank busy fitting for minutes from one that has died.
#pragma once

#include "MpiPolling.h"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace vots::dist {

/// The tag of the heartbeats to rank 0 (empty messages), apart from commands and replies.
inline constexpr int ALIVE_TAG = 7103;
/// How often each process says it lives (rank 0 to the others too, as a command).
inline constexpr auto HEARTBEAT_PERIOD = std::chrono::seconds(2);

/// Ranks > 0: sends rank 0 an empty ALIVE_TAG message every HEARTBEAT_PERIOD while it exists, whatever
/// the rank's main thread is doing; one in flight at a time, so a rank 0 that takes none is not piled up on.
class HeartbeatToRank0 {
public:
    HeartbeatToRank0();
    ~HeartbeatToRank0();
    HeartbeatToRank0(const HeartbeatToRank0&) = delete;
    HeartbeatToRank0& operator=(const HeartbeatToRank0&) = delete;

private:
    void run();
    const std::vector<char> mEmpty;
    MPI_Request mSend = MPI_REQUEST_NULL;
    std::mutex mMutex;
    std::condition_variable mWake;
    bool mStop = false;
    std::thread mThread; // last: started once the rest is built
};

} // namespace vots::dist
