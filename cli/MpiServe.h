// `vots serve` under mpirun: rank 0's FrameCompositor and the other ranks' loop (docs/DESIGN.md §12).
#pragma once

#include "MpiPolling.h"
#include "MpiWorld.h"
#include "SlabDrawer.h"

#include "vots/server/FrameCompositor.h"

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vots::cli {

/// Rank 0's hook: sends each frame (and the eps its slab fit needs) to every other rank, draws its own
/// slab meanwhile, and composites the ranks' float frames as `mpirun vots render` does. A rank that does
/// not answer within the deadline (the frame's, plus a fit's when the eps is new) is taken as lost: the
/// frame and every later one throw RanksLost, logged once; so is a rank whose own heartbeat has stopped
/// for 15 s, which ends a wait for a fit long before its deadline. Only one dataset, the one named at
/// start. A thread tells the other ranks every 2 s that rank 0 lives, so that they leave when it has died,
/// and takes theirs.
class MpiFrameCompositor : public server::FrameCompositor {
public:
    /// Sets MPI_ERRORS_RETURN on the world, so a failing peer gives an error code, not an abort.
    /// `memoryBudget`: the --memory-budget text, which each rank's slab is checked against.
    MpiFrameCompositor(const MpiWorld& world, std::string dataset, std::string memoryBudget);
    ~MpiFrameCompositor() override;
    int ranks() const override { return mWorld.size(); }
    std::string refusal(const std::string& dataset, const render::FrameRequest& frame) const override;
    render::RgbaImage draw(const server::CompositeRequest& request, render::VotRenderer& vots,
                           render::GridRenderer& grid) override;
    server::VolumeSummary summarize(const std::filesystem::path& volumePath) override;
    std::vector<server::RankTimes> lastTimes() const override;
    /// Tells the ranks still answering to leave their loop; after the server (its render thread) is gone.
    void releaseRanks();
    /// True once a rank has been lost: messages to it (its heartbeat, a command) may never complete.
    bool lostARank() const { return mLostRank.load() >= 0; }

private:
    [[noreturn]] void lose(int rank, const std::string& why);
    /// Starts sending `command` to every other rank (one request each, index = rank); loses a rank it
    /// cannot be sent to.
    std::vector<MPI_Request> sendToRanks(const std::vector<char>& command);
    /// Rank r's reply, its command's send being `send`: by `deadline` while r's heartbeat goes on, else r
    /// is lost.
    std::vector<char> replyOf(int r, MPI_Request& send, PollClock::time_point deadline);
    void sendHeartbeats();
    void stopHeartbeats();
    const MpiWorld& mWorld;
    const std::string mDataset;
    SlabDrawer mDrawer;
    std::mutex mExchangeMutex; // one command and its replies at a time (frames, summaries)
    std::string mSentFitKey;   // what the other ranks hold fitted, as far as rank 0 has told them
    std::string mSentGridKey;  // the volume whose planes they hold in their grids
    std::atomic<int> mLostRank = -1;
    std::string mLostMessage;
    mutable std::mutex mTimesMutex;
    std::vector<server::RankTimes> mTimes;
    bool heardLately(int rank) const;
    const std::vector<char> mAlive;                      // the heartbeat message, alive while its sends are
    std::vector<MPI_Request> mAliveSends;                // per rank: the heartbeat in flight
    std::vector<std::atomic<PollClock::rep>> mLastHeard; // per rank: its last heartbeat taken, since epoch
    std::mutex mHeartbeatMutex;
    std::condition_variable mHeartbeatWake;
    bool mStopHeartbeats = false;
    std::thread mHeartbeat; // last: started once the rest is built
};

/// Ranks > 0: fit (or read) and draw this rank's slab for each command from rank 0 and send the float
/// frame back, until rank 0 says quit; throws std::runtime_error when rank 0 has said nothing (not even
/// its heartbeat) for 30 s or does not take a frame within that time. A slab over `memoryBudget` (the
/// --memory-budget text) is refused before it is read, and rank 0 answers 507. A thread sends rank 0 this
/// rank's heartbeat every 2 s meanwhile, also while it fits. Never serves HTTP.
void serveOtherRank(const MpiWorld& world, const std::string& memoryBudget);

} // namespace vots::cli
