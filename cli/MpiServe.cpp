// MpiFrameCompositor and serveOtherRank: frames sent from rank 0, drawn on every rank's slab, combined on
// rank 0 with point-to-point messages polled against a deadline, so a lost rank is noticed, not waited for.
#include "MpiServe.h"

#include "DistributedRender.h"
#include "FrameComposite.h"
#include "MpiHeartbeat.h"
#include "MpiPolling.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/RenderPolicy.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>
#include <type_traits>

namespace vots::cli {
namespace {

using Clock = PollClock;

constexpr int COMMAND_TAG = 7101;
constexpr int REPLY_TAG = 7102;
// The deadlines: a frame of a held fit, and the fit of a new eps besides.
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

enum class CommandKind : std::int32_t { Quit = 0, Frame = 1, Alive = 2, Summary = 3 };

/// A command's fixed part; the volume's path follows it. Ranks are the same binary on the same kind of
/// host, so the frame travels as its bytes.
struct CommandHead {
    CommandKind kind = CommandKind::Quit;
    render::FrameRequest frame;
    float eps = 0.f;
    std::int32_t degree = 3;
    std::array<float, 2> range{0.f, 0.f};
    std::int32_t votsFile = 0; // the path is a .vots file's (server::CompositeRequest::votsFile)
};
static_assert(std::is_trivially_copyable_v<CommandHead>, "commands travel as their bytes");

/// What a rank's error was, so that rank 0 answers as if it were its own: 400, 507 or 500.
enum ErrorKind : std::int32_t { OTHER_ERROR = 0, INPUT_ERROR = 1, OVER_BUDGET = 2 };

/// A reply's fixed part; the error text (ok == 0) or the frame's floats (then the aip's lengths) follow.
struct ReplyHead {
    std::int32_t ok = 0;
    std::int32_t errorKind = 0; // ErrorKind of the error text that follows (ok == 0)
    std::int32_t width = 0;
    std::int32_t height = 0;
    std::int32_t withLengths = 0;
    std::int32_t fromGrid = 0;
    std::int32_t withDisplayRange = 0;
    std::array<float, 2> displayRange{0.f, 0.f}; // SlabFrame::displayRange (withDisplayRange)
    std::uint64_t votCount = 0;                  // of the rank's slab fit (0 for the grid)
    double fitMs = 0.0;                          // or the grid's read of the slab's planes (0 when held)
    double heldFitMs = 0.0;                      // what the slab fit the frame was drawn from took
    double frameMs = 0.0;
};
static_assert(std::is_trivially_copyable_v<ReplyHead>, "replies travel as their bytes");

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

std::vector<float> floatsOf(const SlabFrame& drawn) {
    std::vector<float> floats = drawn.frame.pixels;
    if (drawn.lengths)
        floats.insert(floats.end(), drawn.lengths->pixels.begin(), drawn.lengths->pixels.end());
    return floats;
}

SlabFrame slabFrameOf(const ReplyHead& head, const std::vector<char>& bytes) {
    const std::size_t pixels = static_cast<std::size_t>(head.width) * static_cast<std::size_t>(head.height);
    const std::size_t floats = pixels * (head.withLengths ? 2 : 1);
    if (head.width < 0 || head.height < 0 || bytes.size() != sizeof head + floats * sizeof(float))
        throw std::runtime_error("a rank's frame has the wrong size");
    const auto image = [&](std::size_t first) {
        render::FloatImage out{head.width, head.height, std::vector<float>(pixels)};
        std::memcpy(out.pixels.data(), bytes.data() + sizeof head + first * sizeof(float),
                    pixels * sizeof(float));
        return out;
    };
    SlabFrame drawn{image(0), std::nullopt, head.fromGrid != 0, std::nullopt};
    if (head.withLengths) drawn.lengths = image(pixels);
    if (head.withDisplayRange) drawn.displayRange = head.displayRange;
    return drawn;
}

CommandHead aliveCommand() {
    CommandHead alive;
    alive.kind = CommandKind::Alive;
    return alive;
}

/// What a command asks of one rank: its slab fitted (or its planes read, for the grid) and its frame drawn.
/// Returns the frame; *prepareMs is the fit's or read's time, *drawMs the frame's. `fitProgress`: where
/// the fit reports (rank 0's, for the fit job).
SlabFrame drawRankPart(SlabDrawer& drawer, const CommandHead& head, const std::string& path,
                       render::VotRenderer& vots, render::GridRenderer& grid, double* prepareMs,
                       double* drawMs, const SlabDrawer::Progress& fitProgress = {}) {
    const bool fromGrid = head.frame.renderer == render::RendererKind::Grid;
    const bool cutRays = compositesCutRays(head.frame.mode);
    *prepareMs = fromGrid ? drawer.ensureGrid(path, grid)
                 : head.votsFile
                     ? drawer.ensureVotsFile(path, cutRays, vots)
                     : drawer.ensureFit(path, head.eps, head.degree, head.range, vots, fitProgress);
    const auto start = Clock::now();
    SlabFrame drawn = fromGrid ? SlabDrawer::drawGrid(head.frame, grid) : drawer.draw(head.frame, vots);
    *drawMs = msSince(start);
    return drawn;
}

/// A rank > 0's reply to a Frame or Summary command: its part, or the error that kept it from it.
std::vector<char> replyTo(const CommandHead& head, const std::string& path, SlabDrawer& drawer,
                          render::VotRenderer* vots, render::GridRenderer* grid,
                          const std::string& noRenderer) {
    ReplyHead reply;
    std::string error;
    try {
        if (head.kind == CommandKind::Summary) {
            const SlabSummary summary = drawer.summarize(path);
            reply.ok = 1;
            return messageOf(reply, &summary, sizeof summary);
        }
        if (!vots || !grid) throw std::runtime_error(noRenderer);
        const SlabFrame drawn = drawRankPart(drawer, head, path, *vots, *grid, &reply.fitMs, &reply.frameMs);
        reply.fromGrid = drawn.fromGrid ? 1 : 0;
        reply.votCount = drawn.fromGrid ? 0 : drawer.votCount();
        reply.heldFitMs = drawn.fromGrid ? 0.0 : drawer.fitMs();
        reply.width = drawn.frame.width;
        reply.height = drawn.frame.height;
        reply.withLengths = drawn.lengths ? 1 : 0;
        reply.withDisplayRange = drawn.displayRange ? 1 : 0;
        reply.displayRange = drawn.displayRange.value_or(std::array<float, 2>{0.f, 0.f});
        const std::vector<float> floats = floatsOf(drawn);
        reply.ok = 1;
        return messageOf(reply, floats.data(), floats.size() * sizeof(float));
    } catch (const fit::InputError& e) {
        error = e.what(), reply.errorKind = INPUT_ERROR;
    } catch (const server::RanksOverBudget& e) {
        error = e.what(), reply.errorKind = OVER_BUDGET;
    } catch (const std::exception& e) {
        error = e.what();
    }
    reply.ok = 0;
    return messageOf(reply, error.data(), error.size());
}

} // namespace

MpiFrameCompositor::MpiFrameCompositor(const MpiWorld& world, std::string dataset, std::string memoryBudget)
    : mWorld(world), mDataset(std::move(dataset)),
      mDrawer(world.rank(), world.size(), std::move(memoryBudget)),
      mAlive(messageOf(aliveCommand(), nullptr, 0)),
      mAliveSends(static_cast<std::size_t>(world.size()), MPI_REQUEST_NULL),
      mLastHeard(static_cast<std::size_t>(world.size())) {
    for (auto& heard : mLastHeard)
        heard = Clock::now().time_since_epoch().count();
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    mHeartbeat = std::thread([this] { sendHeartbeats(); });
}

MpiFrameCompositor::~MpiFrameCompositor() {
    stopHeartbeats();
}

void MpiFrameCompositor::sendHeartbeats() {
    std::unique_lock lock(mHeartbeatMutex);
    while (!mStopHeartbeats) {
        for (int r = 1; r < mWorld.size(); ++r) {
            MPI_Request& send = mAliveSends[static_cast<std::size_t>(r)];
            // One at a time to each rank: a rank that takes nothing (lost, or busy with a fit: its queue
            // holds the last one) is not piled up on.
            if (r != mLostRank.load() && sendDone(send)) startSend(mAlive, r, COMMAND_TAG, send);
        }
        for (const int r : takeArrived(ALIVE_TAG))
            if (r > 0 && r < mWorld.size())
                mLastHeard[static_cast<std::size_t>(r)] = Clock::now().time_since_epoch().count();
        mHeartbeatWake.wait_for(lock, HEARTBEAT_PERIOD, [this] { return mStopHeartbeats; });
    }
}

bool MpiFrameCompositor::heardLately(int rank) const {
    const Clock::time_point heard{Clock::duration{mLastHeard[static_cast<std::size_t>(rank)].load()}};
    return Clock::now() - heard < RANK_SILENCE;
}

void MpiFrameCompositor::stopHeartbeats() {
    {
        std::lock_guard lock(mHeartbeatMutex);
        mStopHeartbeats = true;
    }
    mHeartbeatWake.notify_all();
    if (mHeartbeat.joinable()) mHeartbeat.join();
}

std::string MpiFrameCompositor::refusal(const std::string& dataset, const render::FrameRequest&) const {
    if (dataset != mDataset)
        return "under mpirun this server draws only the dataset '" + mDataset + "' (--prepare)";
    return "";
}

void MpiFrameCompositor::lose(int rank, const std::string& why) {
    mLostRank = rank;
    mLostMessage = "rank " + std::to_string(rank) + " of " + std::to_string(mWorld.size()) + " " + why +
                   "; restart the mpirun job";
    std::cerr << "vots serve: " << mLostMessage << " (every frame is refused with 503 from now on)"
              << std::endl;
    throw server::RanksLost(mLostMessage);
}

std::vector<MPI_Request> MpiFrameCompositor::sendToRanks(const std::vector<char>& command) {
    std::vector<MPI_Request> sends(static_cast<std::size_t>(mWorld.size()), MPI_REQUEST_NULL);
    for (int r = 1; r < mWorld.size(); ++r)
        if (!startSend(command, r, COMMAND_TAG, sends[static_cast<std::size_t>(r)]))
            lose(r, "cannot be sent the command");
    return sends;
}

std::vector<char> MpiFrameCompositor::replyOf(int r, MPI_Request& send, PollClock::time_point deadline) {
    const KeepWaiting alive = [this, r] { return heardLately(r); };
    const std::string silent =
        "has sent no heartbeat for " + std::to_string(std::chrono::seconds(RANK_SILENCE).count()) + " s";
    if (!completedBefore(send, deadline, alive))
        lose(r, heardLately(r) ? "did not take the command in time" : silent);
    auto reply = receiveBefore(r, REPLY_TAG, deadline, alive);
    if (!reply) lose(r, heardLately(r) ? "did not answer the frame in time" : silent);
    return std::move(*reply);
}

namespace {

/// A rank's error reply as the exception rank 0 answers with (400 for bad input, else 500).
std::exception_ptr failureOf(int rank, const ReplyHead& head, const std::vector<char>& reply) {
    const std::string text =
        "rank " + std::to_string(rank) + ": " + std::string(reply.begin() + sizeof head, reply.end());
    switch (head.errorKind) {
    case INPUT_ERROR:
        return std::make_exception_ptr(fit::InputError(text));
    case OVER_BUDGET:
        return std::make_exception_ptr(server::RanksOverBudget(text));
    default:
        return std::make_exception_ptr(std::runtime_error(text));
    }
}

} // namespace

render::RgbaImage MpiFrameCompositor::draw(const server::CompositeRequest& request, render::VotRenderer& vots,
                                           render::GridRenderer& grid) {
    std::lock_guard exchange(mExchangeMutex);
    if (mLostRank.load() >= 0) throw server::RanksLost(mLostMessage);
    const auto start = Clock::now();
    const std::string path = request.volumePath.string();
    CommandHead head{CommandKind::Frame, request.frame,      request.eps,
                     request.degree,     request.valueRange, request.votsFile ? 1 : 0};
    // A new fit, or a first read of the planes for the grid, gets the fit's deadline besides the frame's.
    const bool fromGrid = request.frame.renderer == render::RendererKind::Grid;
    std::string& sentKey = fromGrid ? mSentGridKey : mSentFitKey;
    const std::string key = fromGrid ? path
                            : request.votsFile
                                ? SlabDrawer::votsFileKey(path, compositesCutRays(request.frame.mode))
                                : SlabDrawer::fitKey(path, request.eps, request.degree);
    const bool refit = key != sentKey;
    sentKey = key;
    const Clock::time_point deadline = start + FRAME_DEADLINE + (refit ? FIT_DEADLINE : Clock::duration{0});
    const int ranks = mWorld.size();
    std::vector<MPI_Request> sends = sendToRanks(messageOf(head, path.data(), path.size()));

    // This rank's part, while the others draw theirs; a failure here still takes every reply, so that
    // none is left to be read as the next frame's.
    std::vector<server::RankTimes> times(static_cast<std::size_t>(ranks));
    std::optional<FrameComposite> composite;
    std::exception_ptr failure;
    try {
        SlabFrame mine = drawRankPart(mDrawer, head, path, vots, grid, &times[0].fitMs, &times[0].frameMs,
                                      request.fitProgress);
        times[0].votCount = mine.fromGrid ? 0 : mDrawer.votCount();
        times[0].heldFitMs = mine.fromGrid ? 0.0 : mDrawer.fitMs();
        composite.emplace(request.frame.mode, std::move(mine));
    } catch (...) {
        failure = std::current_exception();
    }
    const auto ownEnd = Clock::now();
    for (int r = 1; r < ranks; ++r) {
        server::RankTimes& t = times[static_cast<std::size_t>(r)];
        t.rank = r;
        const std::vector<char> reply = replyOf(r, sends[static_cast<std::size_t>(r)], deadline);
        const auto replyHead = headOf<ReplyHead>(reply);
        t.fitMs = replyHead.fitMs;
        t.frameMs = replyHead.frameMs;
        t.votCount = replyHead.votCount;
        t.heldFitMs = replyHead.heldFitMs;
        if (!replyHead.ok) {
            if (!failure) failure = failureOf(r, replyHead, reply);
            continue;
        }
        try {
            if (composite) composite->add(slabFrameOf(replyHead, reply));
        } catch (...) { // the other ranks' replies are still taken
            if (!failure) failure = std::current_exception();
        }
        t.compositeMs = msSince(ownEnd);
    }
    if (failure) {
        sentKey.clear(); // the next frame gives the fit or read its full deadline again
        std::rethrow_exception(failure);
    }
    const auto finishStart = Clock::now();
    render::FloatImage frame = composite->finish();
    times[0].compositeMs = msSince(finishStart);
    {
        std::lock_guard lock(mTimesMutex);
        mTimes = times;
    }
    // The window of the whole: the volume's range, or the union of the ranks' (box sizes, a file's Vots).
    const std::array<float, 2> range = composite->displayRange().value_or(request.valueRange);
    return render::applyDisplay(frame, render::displayFor(request.frame, range));
}

server::VolumeSummary MpiFrameCompositor::summarize(const std::filesystem::path& volumePath) {
    std::lock_guard exchange(mExchangeMutex);
    if (mLostRank.load() >= 0) throw server::RanksLost(mLostMessage);
    const std::string path = volumePath.string();
    CommandHead head;
    head.kind = CommandKind::Summary;
    // Reading a slab can take as long as fitting it.
    const Clock::time_point deadline = Clock::now() + FRAME_DEADLINE + FIT_DEADLINE;
    std::vector<MPI_Request> sends = sendToRanks(messageOf(head, path.data(), path.size()));
    std::vector<SlabSummary> parts(static_cast<std::size_t>(mWorld.size()));
    std::exception_ptr failure;
    try {
        parts[0] = mDrawer.summarize(path);
    } catch (...) {
        failure = std::current_exception();
    }
    for (int r = 1; r < mWorld.size(); ++r) {
        const std::vector<char> reply = replyOf(r, sends[static_cast<std::size_t>(r)], deadline);
        const auto replyHead = headOf<ReplyHead>(reply);
        if (!replyHead.ok || reply.size() != sizeof replyHead + sizeof(SlabSummary)) {
            if (!failure)
                failure =
                    replyHead.ok
                        ? std::make_exception_ptr(std::runtime_error("a rank's summary has the wrong size"))
                        : failureOf(r, replyHead, reply);
            continue;
        }
        std::memcpy(&parts[static_cast<std::size_t>(r)], reply.data() + sizeof replyHead,
                    sizeof(SlabSummary));
    }
    if (failure) std::rethrow_exception(failure);
    server::VolumeSummary summary{parts[0].range, parts[0].gridCrc};
    for (const SlabSummary& part : parts) {
        summary.range = {std::min(summary.range[0], part.range[0]),
                         std::max(summary.range[1], part.range[1])};
        summary.contentCrc = fit::combineCrc(summary.contentCrc, part.crc, part.bytes);
    }
    return summary;
}

std::vector<server::RankTimes> MpiFrameCompositor::lastTimes() const {
    std::lock_guard lock(mTimesMutex);
    return mTimes;
}

void MpiFrameCompositor::releaseRanks() {
    stopHeartbeats();
    const CommandHead quit{};
    const std::vector<char> command = messageOf(quit, nullptr, 0);
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

void serveOtherRank(const MpiWorld& world, const std::string& memoryBudget) {
    // Without a renderer this rank still answers every frame (with the reason), so rank 0 never waits.
    std::unique_ptr<render::EglContext> context;
    std::unique_ptr<render::VotRenderer> vots;
    std::unique_ptr<render::GridRenderer> grid;
    std::string noRenderer;
    try {
        context = render::EglContext::createOrThrow();
        vots = std::make_unique<render::VotRenderer>();
        server::applyRenderPolicy(*vots);
        grid = std::make_unique<render::GridRenderer>();
    } catch (const std::exception& e) {
        noRenderer = std::string("no renderer: ") + e.what();
    }
    const HeartbeatToRank0 heartbeat;
    SlabDrawer drawer(world.rank(), world.size(), memoryBudget);
    const std::string self =
        "vots serve: rank " + std::to_string(world.rank()) + " of " + std::to_string(world.size());
    const std::string silence = std::to_string(std::chrono::seconds(RANK0_SILENCE).count());
    for (;;) {
        const auto command = receiveBefore(0, COMMAND_TAG, Clock::now() + RANK0_SILENCE);
        if (!command)
            throw std::runtime_error(self + ": rank 0 has sent nothing for " + silence + " s; leaving");
        const auto head = headOf<CommandHead>(*command);
        if (head.kind == CommandKind::Quit) { // said back, so that rank 0 finalizes only after it is taken
            const std::vector<char> taken = messageOf(ReplyHead{}, nullptr, 0);
            MPI_Request send = MPI_REQUEST_NULL;
            if (startSend(taken, 0, REPLY_TAG, send)) completedBefore(send, Clock::now() + RELEASE_DEADLINE);
            return;
        }
        if (head.kind == CommandKind::Alive) continue;
        const std::string path(command->begin() + sizeof head, command->end());
        const std::vector<char> bytes = replyTo(head, path, drawer, vots.get(), grid.get(), noRenderer);
        MPI_Request send = MPI_REQUEST_NULL;
        if (!startSend(bytes, 0, REPLY_TAG, send) || !completedBefore(send, Clock::now() + RANK0_SILENCE))
            throw std::runtime_error(self + ": rank 0 did not take the frame within " + silence +
                                     " s; leaving");
    }
}

} // namespace vots::cli
