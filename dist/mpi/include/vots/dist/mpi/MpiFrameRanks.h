// `vots serve` under mpirun: rank 0's FrameRanks, which reaches the other ranks with point-to-point
// messages, and the other ranks' loop.
#pragma once

#include "vots/dist/FrameRanks.h"
#include "vots/dist/RankPart.h"
#include "vots/dist/mpi/MpiWorld.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace vots::render {
class VotRenderer;
}

namespace vots::dist {

/// Rank 0's port: sends each fit and frame to every other rank, does its own part meanwhile, and
/// composites the ranks' float frames as `mpirun vots render` does. A frame of a fit the ranks do not
/// hold is two rounds: the fit, whose background sums give the whole volume's fill, then the frame drawn
/// with it. A rank that does not answer within the deadline (the frame's, plus a fit's when the eps is
/// new) is taken as lost: the frame and every later one throw RanksLost, logged once; so is a rank whose
/// own heartbeat has stopped for 15 s, which ends a wait for a fit long before its deadline. Only one
/// dataset, the one named at start. A thread tells the other ranks every 2 s that rank 0 lives, so that
/// they leave when it has died, and takes theirs.
class MpiFrameRanks : public FrameRanks {
public:
    /// Sets MPI_ERRORS_RETURN on the world, so a failing peer gives an error code, not an abort.
    MpiFrameRanks(const MpiWorld& world, std::string dataset, RankSetup setup);
    ~MpiFrameRanks() override;
    int ranks() const override { return mWorld.size(); }
    std::string refusal(const std::string& dataset, const render::FrameRequest& frame) const override;
    ComposedFrame draw(const DrawRequest& request, render::VotRenderer& vots,
                       render::GridRenderer& grid) override;
    RanksFit fit(const FitRequest& request, const FitProgress& progress) override;
    VolumeSummary summarize(const std::filesystem::path& volumePath, int frame) override;
    std::vector<RankTimes> lastTimes() const override;
    /// Tells the ranks still answering to leave their loop; after the server (its render thread) is gone.
    void releaseRanks();
    /// True once a rank has been lost: messages to it (its heartbeat, a command) may never complete.
    bool lostARank() const { return mLostRank.load() >= 0; }

private:
    struct Exchange;
    [[noreturn]] void lose(int rank, const std::string& why);
    /// Sends `command` to every other rank and has `mine` do this rank's part meanwhile; then takes every
    /// rank's reply by `deadline` (giving each to `take` with its rank) and rethrows the first failure,
    /// after every reply is taken, so that none is left to be read as the next command's.
    void exchange(const std::vector<char>& command, std::chrono::steady_clock::time_point deadline,
                  const std::function<void()>& mine,
                  const std::function<void(int rank, const std::vector<char>& reply)>& take);
    /// The fit round: every rank fits its cells (this one reporting through `progress`); the fill of the
    /// whole is kept for the frames of that fit.
    RanksFit fitOnRanks(const FitRequest& request, const FitProgress& progress);
    void sendHeartbeats();
    void stopHeartbeats();
    bool heardLately(int rank) const;
    const MpiWorld& mWorld;
    const std::string mDataset;
    RankPart mPart;
    std::mutex mExchangeMutex;        // one command and its replies at a time (fits, frames, summaries)
    std::string mFittedId;            // RankPart::cellsFitId every rank holds fitted, as far as rank 0 knows
    std::optional<float> mFittedFill; // the whole volume's fill of that fit
    std::vector<double> mFitRoundMs;  // per rank: the last fit round's fitting (0 when held)
    std::string mSentFileId;          // the .vots file's Vots the ranks hold uploaded
    std::string mSentGridPath;        // the volume and frame ("path|frame") whose planes their grids hold
    std::atomic<int> mLostRank = -1;
    std::string mLostMessage;
    mutable std::mutex mTimesMutex;
    std::vector<RankTimes> mTimes;
    struct Heartbeats;
    std::unique_ptr<Heartbeats> mHeartbeats;
    std::vector<std::atomic<std::chrono::steady_clock::rep>> mLastHeard; // per rank, since epoch
    std::mutex mHeartbeatMutex;
    std::condition_variable mHeartbeatWake;
    bool mStopHeartbeats = false;
    std::thread mHeartbeat; // last: started once the rest is built
};

/// Ranks > 0: fit, read and draw this rank's cells for each command from rank 0 and send the result
/// back, until rank 0 says quit; throws std::runtime_error when rank 0 has said nothing (not even its
/// heartbeat) for 30 s or does not take a reply within that time. Cells over the memory budget are refused
/// before they are read, and rank 0 answers 507. A thread sends rank 0 this rank's heartbeat every 2 s
/// meanwhile, also while it fits. `configureRenderer`: applied to this rank's VotRenderer once made (the
/// server's render policy). Never serves HTTP.
void serveOtherRank(const MpiWorld& world, RankSetup setup,
                    const std::function<void(render::VotRenderer&)>& configureRenderer);

} // namespace vots::dist
