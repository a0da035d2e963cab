// MpiFrameCompositor and serveOtherRank: frames sent from rank 0, drawn on every rank's slab, combined on
// rank 0 with point-to-point messages polled against a deadline, so a lost rank is noticed, not waited for.
#include "MpiServe.h"

#include "FrameComposite.h"

#include "vots/fit/Error.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/RenderPolicy.h"

#include <mpi.h>

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

using Clock = std::chrono::steady_clock;

constexpr int COMMAND_TAG = 7101;
constexpr int REPLY_TAG = 7102;
// Polling, not blocking: Open MPI's blocking calls spin a core, and a rank that has died never completes
// them. The deadlines: a frame of a held fit, and the fit of a new eps besides.
constexpr auto POLL_PERIOD = std::chrono::milliseconds(2);
constexpr auto FRAME_DEADLINE = std::chrono::seconds(10);
constexpr auto FIT_DEADLINE = std::chrono::minutes(10);
constexpr auto RELEASE_DEADLINE = std::chrono::seconds(2);

enum class CommandKind : std::int32_t { Quit = 0, Frame = 1 };

/// A command's fixed part; the volume's path follows it. Ranks are the same binary on the same kind of
/// host, so the frame travels as its bytes.
struct CommandHead {
    CommandKind kind = CommandKind::Quit;
    render::FrameRequest frame;
    float eps = 0.f;
    std::int32_t degree = 3;
    std::array<float, 2> range{0.f, 0.f};
};
static_assert(std::is_trivially_copyable_v<CommandHead>, "commands travel as their bytes");

/// A reply's fixed part; the error text (ok == 0) or the frame's floats (then the aip's lengths) follow.
struct ReplyHead {
    std::int32_t ok = 0;
    std::int32_t errorIsInput = 0; // a fit::InputError: the request's fault, answered 400
    std::int32_t width = 0;
    std::int32_t height = 0;
    std::int32_t withLengths = 0;
    double fitMs = 0.0;
    double frameMs = 0.0;
};
static_assert(std::is_trivially_copyable_v<ReplyHead>, "replies travel as their bytes");

template <typename Head>
std::vector<char> messageOf(const Head& head, const void* tail, std::size_t tailBytes) {
    std::vector<char> bytes(sizeof head + tailBytes);
    std::memcpy(bytes.data(), &head, sizeof head);
    if (tailBytes) std::memcpy(bytes.data() + sizeof head, tail, tailBytes);
    return bytes;
}

template <typename Head> Head headOf(const std::vector<char>& bytes) {
    if (bytes.size() < sizeof(Head)) throw std::runtime_error("a rank's message is too short");
    Head head;
    std::memcpy(&head, bytes.data(), sizeof head);
    return head;
}

/// Waits for a message from `source` until `deadline` (none: for ever); nullopt when none came or MPI
/// reports an error.
std::optional<std::vector<char>> receiveBefore(int source, int tag,
                                               std::optional<Clock::time_point> deadline) {
    for (;;) {
        int arrived = 0;
        MPI_Status status;
        if (MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status) != MPI_SUCCESS) return std::nullopt;
        if (arrived) {
            int count = 0;
            MPI_Get_count(&status, MPI_BYTE, &count);
            std::vector<char> bytes(static_cast<std::size_t>(count));
            if (MPI_Recv(bytes.data(), count, MPI_BYTE, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE) !=
                MPI_SUCCESS)
                return std::nullopt;
            return bytes;
        }
        if (deadline && Clock::now() >= *deadline) return std::nullopt;
        std::this_thread::sleep_for(POLL_PERIOD);
    }
}

/// Completes a nonblocking send by `deadline`; false when it did not (the request is left to MPI).
bool completedBefore(MPI_Request& request, Clock::time_point deadline) {
    for (;;) {
        int done = 0;
        if (MPI_Test(&request, &done, MPI_STATUS_IGNORE) != MPI_SUCCESS) return false;
        if (done) return true;
        if (Clock::now() >= deadline) return false;
        std::this_thread::sleep_for(POLL_PERIOD);
    }
}

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
    SlabFrame drawn{image(0), std::nullopt};
    if (head.withLengths) drawn.lengths = image(pixels);
    return drawn;
}

} // namespace

MpiFrameCompositor::MpiFrameCompositor(const MpiWorld& world, std::string dataset)
    : mWorld(world), mDataset(std::move(dataset)), mDrawer(world.rank(), world.size()) {
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

std::string MpiFrameCompositor::refusal(const std::string& dataset, const render::FrameRequest& frame) const {
    if (dataset != mDataset)
        return "under mpirun this server draws only the dataset '" + mDataset + "' (--prepare)";
    if (frame.renderer == render::RendererKind::Grid)
        return "under mpirun the frames are drawn from the ranks' Vots: not --renderer grid or reference";
    if (frame.mode == render::RenderMode::Density) return "under mpirun the density is not composited yet";
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

render::RgbaImage MpiFrameCompositor::draw(const server::CompositeRequest& request,
                                           render::VotRenderer& vots) {
    if (mLostRank >= 0) throw server::RanksLost(mLostMessage);
    const auto start = Clock::now();
    const std::string path = request.volumePath.string();
    CommandHead head{CommandKind::Frame, request.frame, request.eps, request.degree, request.valueRange};
    const std::vector<char> command = messageOf(head, path.data(), path.size());
    const std::string fitKey = SlabDrawer::fitKey(path, request.eps, request.degree);
    const bool refit = fitKey != mSentFitKey;
    mSentFitKey = fitKey;
    const Clock::time_point deadline = start + FRAME_DEADLINE + (refit ? FIT_DEADLINE : Clock::duration{0});
    const int ranks = mWorld.size();
    std::vector<MPI_Request> sends(static_cast<std::size_t>(ranks), MPI_REQUEST_NULL);
    for (int r = 1; r < ranks; ++r)
        if (MPI_Isend(command.data(), static_cast<int>(command.size()), MPI_BYTE, r, COMMAND_TAG,
                      MPI_COMM_WORLD, &sends[static_cast<std::size_t>(r)]) != MPI_SUCCESS)
            lose(r, "cannot be sent the frame");

    // This rank's part, while the others draw theirs; a failure here still takes every reply, so that
    // none is left to be read as the next frame's.
    std::vector<server::RankTimes> times(static_cast<std::size_t>(ranks));
    std::optional<FrameComposite> composite;
    std::exception_ptr failure;
    try {
        times[0].fitMs = mDrawer.ensureFit(path, request.eps, request.degree, request.valueRange, vots);
        const auto drawStart = Clock::now();
        SlabFrame mine = mDrawer.draw(request.frame, vots);
        times[0].frameMs = msSince(drawStart);
        composite.emplace(request.frame.mode, std::move(mine));
    } catch (...) {
        failure = std::current_exception();
    }
    const auto ownEnd = Clock::now();
    for (int r = 1; r < ranks; ++r) {
        server::RankTimes& t = times[static_cast<std::size_t>(r)];
        t.rank = r;
        if (!completedBefore(sends[static_cast<std::size_t>(r)], deadline))
            lose(r, "did not take the frame in time");
        const auto reply = receiveBefore(r, REPLY_TAG, deadline);
        if (!reply) lose(r, "did not answer the frame in time");
        const auto replyHead = headOf<ReplyHead>(*reply);
        t.fitMs = replyHead.fitMs;
        t.frameMs = replyHead.frameMs;
        if (!replyHead.ok) {
            if (failure) continue;
            const std::string text = "rank " + std::to_string(r) + ": " +
                                     std::string(reply->begin() + sizeof replyHead, reply->end());
            failure = replyHead.errorIsInput ? std::make_exception_ptr(fit::InputError(text))
                                             : std::make_exception_ptr(std::runtime_error(text));
            continue;
        }
        try {
            if (composite) composite->add(slabFrameOf(replyHead, *reply));
        } catch (...) { // the other ranks' replies are still taken
            if (!failure) failure = std::current_exception();
        }
        t.compositeMs = msSince(ownEnd);
    }
    if (failure) {
        mSentFitKey.clear(); // the next frame gives the fit its full deadline again
        std::rethrow_exception(failure);
    }
    const auto finishStart = Clock::now();
    render::FloatImage frame = composite->finish();
    times[0].compositeMs = msSince(finishStart);
    {
        std::lock_guard lock(mTimesMutex);
        mTimes = times;
    }
    return render::applyDisplay(frame, render::displayFor(request.frame, request.valueRange));
}

std::vector<server::RankTimes> MpiFrameCompositor::lastTimes() const {
    std::lock_guard lock(mTimesMutex);
    return mTimes;
}

void MpiFrameCompositor::releaseRanks() {
    const CommandHead quit{};
    const std::vector<char> command = messageOf(quit, nullptr, 0);
    const auto deadline = Clock::now() + RELEASE_DEADLINE;
    for (int r = 1; r < mWorld.size(); ++r) {
        if (r == mLostRank) continue;
        MPI_Request send = MPI_REQUEST_NULL;
        if (MPI_Isend(command.data(), static_cast<int>(command.size()), MPI_BYTE, r, COMMAND_TAG,
                      MPI_COMM_WORLD, &send) == MPI_SUCCESS &&
            !completedBefore(send, deadline))
            std::cerr << "vots serve: rank " << r << " did not take the quit\n";
    }
}

void serveOtherRank(const MpiWorld& world) {
    // Without a renderer this rank still answers every frame (with the reason), so rank 0 never waits.
    std::unique_ptr<render::EglContext> context;
    std::unique_ptr<render::VotRenderer> vots;
    std::string noRenderer;
    try {
        context = render::EglContext::createOrThrow();
        vots = std::make_unique<render::VotRenderer>();
        server::applyRenderPolicy(*vots);
    } catch (const std::exception& e) {
        noRenderer = std::string("no renderer: ") + e.what();
    }
    SlabDrawer drawer(world.rank(), world.size());
    for (;;) {
        const auto command = receiveBefore(0, COMMAND_TAG, std::nullopt);
        if (!command) throw std::runtime_error("rank " + std::to_string(world.rank()) + ": lost rank 0");
        const auto head = headOf<CommandHead>(*command);
        if (head.kind == CommandKind::Quit) return;
        const std::string path(command->begin() + sizeof head, command->end());
        ReplyHead reply;
        std::vector<float> floats;
        std::string error;
        try {
            if (!vots) throw std::runtime_error(noRenderer);
            reply.fitMs = drawer.ensureFit(path, head.eps, head.degree, head.range, *vots);
            const auto drawStart = Clock::now();
            const SlabFrame drawn = drawer.draw(head.frame, *vots);
            reply.frameMs = msSince(drawStart);
            reply.width = drawn.frame.width;
            reply.height = drawn.frame.height;
            reply.withLengths = drawn.lengths ? 1 : 0;
            floats = floatsOf(drawn);
            reply.ok = 1;
        } catch (const fit::InputError& e) {
            error = e.what(), reply.errorIsInput = 1;
        } catch (const std::exception& e) {
            error = e.what();
        }
        const std::vector<char> bytes = reply.ok
                                            ? messageOf(reply, floats.data(), floats.size() * sizeof(float))
                                            : messageOf(reply, error.data(), error.size());
        MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, REPLY_TAG, MPI_COMM_WORLD);
    }
}

} // namespace vots::cli
