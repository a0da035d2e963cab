// MpiFrameRanks and serveOtherRank: fits and frames sent from rank 0, done on every rank's cells,
// combined on rank 0 with point-to-point messages polled against a deadline, so a lost rank is noticed,
// not waited for.
#include "vots/dist/mpi/MpiFrameRanks.h"

#include "MpiHeartbeat.h"
#include "MpiPolling.h"
#include "RankCommands.h"
#include "RankWork.h"

#include "vots/dist/CompositeOp.h"
#include "vots/dist/FrameComposite.h"
#include "vots/dist/WholeFill.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <exception>
#include <iostream>

namespace vots::dist {
namespace {

using Clock = PollClock;

// The deadlines: a frame of a held fit, and a fit (or a first read) besides.
constexpr auto FRAME_DEADLINE = std::chrono::seconds(10);
constexpr auto FIT_DEADLINE = std::chrono::minutes(10);
constexpr auto RELEASE_DEADLINE = std::chrono::seconds(2);
// Rank 0 says it is alive every HEARTBEAT_PERIOD, and the other ranks leave when it has said nothing for
// longer than the silence: a rank 0 that died would otherwise leave them waiting for commands, and mpirun
// with them.
constexpr auto RANK0_SILENCE = std::chrono::seconds(30);
// The other ranks say so too, from a thread of their own, so that rank 0 tells a rank still fitting (for
// minutes, under the fit's deadline) from one that has died, and answers 503 soon after the death.
constexpr auto RANK_SILENCE = std::chrono::seconds(15);

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<char> commandOf(MessageKind kind, const CommandBody& body, const std::string& path) {
    return messageOf(kind, body, path.data(), path.size());
}

/// A rank's FAILED reply as the exception rank 0 throws for it.
std::exception_ptr failureOfReply(int rank, const std::vector<char>& reply) {
    const FailedBody body = bodyOf<FailedBody>(reply, FAILED);
    return failureOf(failureKindFromWire(body.kind), "rank " + std::to_string(rank) + ": " + tailOf(reply));
}

} // namespace

struct MpiFrameRanks::Heartbeats {
    std::vector<char> alive = commandOf(ALIVE, CommandBody{}, ""); // alive while its sends are
    std::vector<MPI_Request> sends;                                // per rank: the heartbeat in flight
};

MpiFrameRanks::MpiFrameRanks(const MpiWorld& world, std::string dataset, RankSetup setup)
    : mWorld(world), mDataset(std::move(dataset)), mPart(world.rank(), world.size(), std::move(setup)),
      mHeartbeats(std::make_unique<Heartbeats>()), mLastHeard(static_cast<std::size_t>(world.size())) {
    mHeartbeats->sends.assign(static_cast<std::size_t>(world.size()), MPI_REQUEST_NULL);
    for (auto& heard : mLastHeard)
        heard = Clock::now().time_since_epoch().count();
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    mHeartbeat = std::thread([this] { sendHeartbeats(); });
}

MpiFrameRanks::~MpiFrameRanks() {
    stopHeartbeats();
}

void MpiFrameRanks::sendHeartbeats() {
    std::unique_lock lock(mHeartbeatMutex);
    while (!mStopHeartbeats) {
        for (int r = 1; r < mWorld.size(); ++r) {
            MPI_Request& send = mHeartbeats->sends[static_cast<std::size_t>(r)];
            // One at a time to each rank: a rank that takes nothing (lost, or busy with a fit: its queue
            // holds the last one) is not piled up on.
            if (r != mLostRank.load() && sendDone(send)) startSend(mHeartbeats->alive, r, COMMAND_TAG, send);
        }
        for (const int r : takeArrived(ALIVE_TAG))
            if (r > 0 && r < mWorld.size())
                mLastHeard[static_cast<std::size_t>(r)] = Clock::now().time_since_epoch().count();
        mHeartbeatWake.wait_for(lock, HEARTBEAT_PERIOD, [this] { return mStopHeartbeats; });
    }
}

bool MpiFrameRanks::heardLately(int rank) const {
    const Clock::time_point heard{Clock::duration{mLastHeard[static_cast<std::size_t>(rank)].load()}};
    return Clock::now() - heard < RANK_SILENCE;
}

void MpiFrameRanks::stopHeartbeats() {
    {
        std::lock_guard lock(mHeartbeatMutex);
        mStopHeartbeats = true;
    }
    mHeartbeatWake.notify_all();
    if (mHeartbeat.joinable()) mHeartbeat.join();
}

std::string MpiFrameRanks::refusal(const std::string& dataset, const render::FrameRequest&) const {
    if (dataset != mDataset)
        return "under mpirun this server draws only the dataset '" + mDataset + "' (--prepare)";
    return "";
}

void MpiFrameRanks::lose(int rank, const std::string& why) {
    mLostRank = rank;
    mLostMessage = "rank " + std::to_string(rank) + " of " + std::to_string(mWorld.size()) + " " + why +
                   "; restart the mpirun job";
    std::cerr << "vots serve: " << mLostMessage << " (every frame is refused with 503 from now on)"
              << std::endl;
    throw RanksLost(mLostMessage);
}

void MpiFrameRanks::exchange(const std::vector<char>& command, Clock::time_point deadline,
                             const std::function<void()>& mine,
                             const std::function<void(int, const std::vector<char>&)>& take) {
    if (mLostRank.load() >= 0) throw RanksLost(mLostMessage);
    std::vector<MPI_Request> sends(static_cast<std::size_t>(mWorld.size()), MPI_REQUEST_NULL);
    for (int r = 1; r < mWorld.size(); ++r)
        if (!startSend(command, r, COMMAND_TAG, sends[static_cast<std::size_t>(r)]))
            lose(r, "cannot be sent the command");
    // This rank's part, while the others do theirs; a failure here still takes every reply.
    std::exception_ptr failure;
    try {
        mine();
    } catch (...) {
        failure = std::current_exception();
    }
    const std::string silent =
        "has sent no heartbeat for " + std::to_string(std::chrono::seconds(RANK_SILENCE).count()) + " s";
    for (int r = 1; r < mWorld.size(); ++r) {
        const KeepWaiting alive = [this, r] { return heardLately(r); };
        if (!completedBefore(sends[static_cast<std::size_t>(r)], deadline, alive))
            lose(r, heardLately(r) ? "did not take the command in time" : silent);
        const auto reply = receiveBefore(r, REPLY_TAG, deadline, alive);
        if (!reply) lose(r, heardLately(r) ? "did not answer in time" : silent);
        try {
            if (headOf(*reply).kind == FAILED) std::rethrow_exception(failureOfReply(r, *reply));
            take(r, *reply);
        } catch (...) { // the other ranks' replies are still taken
            if (!failure) failure = std::current_exception();
        }
    }
    if (failure) std::rethrow_exception(failure);
}

RanksFit MpiFrameRanks::fitOnRanks(const FitRequest& request, const FitProgress& progress) {
    const std::string path = request.volumePath.string();
    CommandBody command;
    command.eps = request.eps;
    command.degree = request.degree;
    command.norm = static_cast<std::int32_t>(request.norm);
    command.range = request.valueRange;
    command.volumeFrame = request.frame;
    std::vector<BackgroundSums> sums(static_cast<std::size_t>(mWorld.size()));
    RanksFit done;
    double slowestMs = 0.0;
    mFitRoundMs.assign(static_cast<std::size_t>(mWorld.size()), 0.0);
    const auto add = [&](int rank, const FittedBody& fitted) {
        sums[static_cast<std::size_t>(rank)] = {fitted.backgroundCells, fitted.backgroundValueSum};
        mFitRoundMs[static_cast<std::size_t>(rank)] = fitted.fitMs;
        done.votCount += fitted.votCount;
        slowestMs = std::max(slowestMs, fitted.heldFitMs);
    };
    mFittedId.clear(); // until every rank has it
    exchange(
        commandOf(FIT, command, path), Clock::now() + FRAME_DEADLINE + FIT_DEADLINE,
        [&] {
            const RankFit mine = mPart.fit(path, request.frame, request.eps, request.degree, request.norm,
                                           request.valueRange, progress);
            add(0, fittedBodyOf(mine));
        },
        [&](int rank, const std::vector<char>& reply) { add(rank, bodyOf<FittedBody>(reply, FITTED)); });
    mFittedFill = wholeVolumeFill(sums);
    mFittedId = RankPart::cellsFitId(path, request.frame, request.eps, request.degree, request.norm);
    done.seconds = slowestMs / 1000.0;
    return done;
}

RanksFit MpiFrameRanks::fit(const FitRequest& request, const FitProgress& progress) {
    std::lock_guard lock(mExchangeMutex);
    return fitOnRanks(request, progress);
}

ComposedFrame MpiFrameRanks::draw(const DrawRequest& request, render::VotRenderer& vots,
                                  render::GridRenderer& grid) {
    std::lock_guard lock(mExchangeMutex);
    const std::string path = request.fit.volumePath.string();
    const bool fromGrid = request.frame.renderer == render::RendererKind::Grid;
    CommandBody command;
    command.frame = request.frame;
    command.eps = request.fit.eps;
    command.degree = request.fit.degree;
    command.norm = static_cast<std::int32_t>(request.fit.norm);
    command.range = request.fit.valueRange;
    command.votsFile = request.votsFile ? 1 : 0;
    command.volumeFrame = request.fit.frame;
    // A frame of Vots the ranks must first read (a file, the grid's planes) or upload gets a fit's deadline.
    bool firstOfItsInput = false;
    mFitRoundMs.assign(static_cast<std::size_t>(mWorld.size()), 0.0);
    if (fromGrid) {
        const std::string sent = path + '|' + std::to_string(request.fit.frame);
        firstOfItsInput = sent != mSentGridPath;
        mSentGridPath = sent;
    } else if (request.votsFile) {
        const std::string id = RankPart::votsFileId(path, compositesCutRays(request.frame.mode));
        firstOfItsInput = id != mSentFileId;
        mSentFileId = id;
    } else {
        if (RankPart::cellsFitId(path, request.fit.frame, request.fit.eps, request.fit.degree,
                                 request.fit.norm) != mFittedId) {
            fitOnRanks(request.fit, {});
            firstOfItsInput = true;
        }
        command.hasFill = mFittedFill ? 1 : 0;
        command.fill = mFittedFill.value_or(0.f);
    }
    const Clock::time_point deadline =
        Clock::now() + FRAME_DEADLINE + (firstOfItsInput ? FIT_DEADLINE : Clock::duration{0});

    std::vector<RankTimes> times(static_cast<std::size_t>(mWorld.size()));
    for (int r = 0; r < mWorld.size(); ++r)
        times[static_cast<std::size_t>(r)].rank = r;
    std::optional<FrameComposite> composite;
    Clock::time_point ownEnd;
    try {
        exchange(
            commandOf(FRAME, command, path), deadline,
            [&] {
                RankTimes& t = times[0];
                RankFrame mine = drawPart(mPart, command, path, vots, grid, &t.fitMs, &t.frameMs);
                t.fitMs += mFitRoundMs[0];
                t.votCount = fromGrid ? 0 : mPart.votCount();
                t.heldFitMs = fromGrid ? 0.0 : mPart.fitMs();
                ownEnd = Clock::now();
                composite.emplace(request.frame.mode, std::move(mine));
            },
            [&](int rank, const std::vector<char>& reply) {
                const DrawnBody body = bodyOf<DrawnBody>(reply, DRAWN);
                RankTimes& t = times[static_cast<std::size_t>(rank)];
                t.fitMs = body.readMs + mFitRoundMs[static_cast<std::size_t>(rank)];
                t.frameMs = body.frameMs;
                t.votCount = body.votCount;
                t.heldFitMs = body.heldFitMs;
                if (composite) composite->add(rankFrameOf(body, reply));
                t.compositeMs = msSince(ownEnd);
            });
    } catch (...) {
        // The next frame gives the reads and uploads their full deadline again.
        mSentGridPath.clear();
        mSentFileId.clear();
        throw;
    }
    const auto finishStart = Clock::now();
    ComposedFrame composed;
    composed.image = composite->finish();
    times[0].compositeMs = msSince(finishStart);
    {
        std::lock_guard timesLock(mTimesMutex);
        mTimes = std::move(times);
    }
    // The window of the whole: the volume's range, or the union of the ranks' (box sizes, a file's Vots).
    composed.displayRange = composite->displayRange().value_or(request.fit.valueRange);
    return composed;
}

VolumeSummary MpiFrameRanks::summarize(const std::filesystem::path& volumePath, int frame) {
    std::lock_guard lock(mExchangeMutex);
    const std::string path = volumePath.string();
    std::vector<RankSummary> parts(static_cast<std::size_t>(mWorld.size()));
    CommandBody command;
    command.volumeFrame = frame;
    // Reading a rank's planes can take as long as fitting them.
    exchange(
        commandOf(SUMMARY, command, path), Clock::now() + FRAME_DEADLINE + FIT_DEADLINE,
        [&] { parts[0] = mPart.summarize(path, frame); },
        [&](int rank, const std::vector<char>& reply) {
            parts[static_cast<std::size_t>(rank)] = bodyOf<RankSummary>(reply, SUMMARIZED);
        });
    VolumeSummary summary{parts[0].range, parts[0].gridCrc};
    for (const RankSummary& part : parts) {
        summary.range = {std::min(summary.range[0], part.range[0]),
                         std::max(summary.range[1], part.range[1])};
        summary.contentCrc = fit::combineCrc(summary.contentCrc, part.crc, part.bytes);
    }
    return summary;
}

std::vector<RankTimes> MpiFrameRanks::lastTimes() const {
    std::lock_guard lock(mTimesMutex);
    return mTimes;
}

void MpiFrameRanks::releaseRanks() {
    stopHeartbeats();
    const std::vector<char> command = commandOf(QUIT, CommandBody{}, "");
    const auto deadline = Clock::now() + RELEASE_DEADLINE;
    for (int r = 1; r < mWorld.size(); ++r) {
        if (r == mLostRank.load()) continue;
        // Waited for: a message still on its way when this process finalizes and exits can be dropped by
        // Open MPI as from a failed peer (seen: rank 1 then waited out its 30 s of silence).
        MPI_Request send = MPI_REQUEST_NULL;
        if (!startSend(command, r, COMMAND_TAG, send) || !completedBefore(send, deadline) ||
            !receiveBefore(r, REPLY_TAG, deadline))
            std::cerr << "vots serve: rank " << r << " did not take the quit\n";
    }
}

void serveOtherRank(const MpiWorld& world, RankSetup setup,
                    const std::function<void(render::VotRenderer&)>& configureRenderer) {
    // Without a renderer this rank still answers every frame (with the reason), so rank 0 never waits.
    std::unique_ptr<render::EglContext> context;
    std::unique_ptr<render::VotRenderer> vots;
    std::unique_ptr<render::GridRenderer> grid;
    std::string noRenderer;
    try {
        context = render::EglContext::createOrThrow();
        vots = std::make_unique<render::VotRenderer>();
        if (configureRenderer) configureRenderer(*vots);
        grid = std::make_unique<render::GridRenderer>();
    } catch (const std::exception& e) {
        noRenderer = std::string("no renderer: ") + e.what();
    }
    const HeartbeatToRank0 heartbeat;
    RankPart part(world.rank(), world.size(), std::move(setup));
    const std::string self =
        "vots serve: rank " + std::to_string(world.rank()) + " of " + std::to_string(world.size());
    const std::string silence = std::to_string(std::chrono::seconds(RANK0_SILENCE).count());
    for (;;) {
        const auto command = receiveBefore(0, COMMAND_TAG, Clock::now() + RANK0_SILENCE);
        if (!command)
            throw std::runtime_error(self + ": rank 0 has sent nothing for " + silence + " s; leaving");
        // A command this build does not read ends the rank: rank 0 is another vots, and waits in vain.
        const auto kind = static_cast<MessageKind>(headOf(*command).kind);
        const CommandBody body = bodyOf<CommandBody>(*command, kind);
        if (kind == QUIT) { // said back, so that rank 0 finalizes only after it is taken
            const std::vector<char> taken = messageOf(QUIT_TAKEN, EmptyBody{});
            MPI_Request send = MPI_REQUEST_NULL;
            if (startSend(taken, 0, REPLY_TAG, send)) completedBefore(send, Clock::now() + RELEASE_DEADLINE);
            return;
        }
        if (kind == ALIVE) continue;
        const std::string path = tailOf(*command);
        const std::vector<char> bytes = replyTo(kind, body, path, part, vots.get(), grid.get(), noRenderer);
        MPI_Request send = MPI_REQUEST_NULL;
        if (!startSend(bytes, 0, REPLY_TAG, send) || !completedBefore(send, Clock::now() + RANK0_SILENCE))
            throw std::runtime_error(self + ": rank 0 did not take the reply within " + silence +
                                     " s; leaving");
    }
}

} // namespace vots::dist
