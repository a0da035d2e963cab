// The one render thread: owns the EglContext and renderers; handlers post jobs and wait on a future.
#pragma once

#include "frames/OwnerTurns.h"
#include "routes/Params.h"
#include "vots/dist/FrameRanks.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/Image.h"

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace vots::server {

class ForegroundActivity;
class ServerStats;

/// What to draw. The Vot-Space is needed for mip and density, the volume for reference and the
/// default window (full data range).
struct RenderJob {
    RenderParams params;
    std::shared_ptr<const fit::VotSpace> space;
    std::shared_ptr<const fit::Volume> volume;
    // The volume's min and max sample, as the registry keeps it, so that no frame scans the volume;
    // nullopt: the Vot-Space's own range (a .vots dataset, as `vots render FILE.vots` draws it).
    std::optional<std::array<float, 2>> valueRange;
    // Set when the ranks draw the frame (dist::FrameRanks): its request. `space` is then null, or a .vots
    // dataset's (only its count and meta are read: the ranks draw their own Vots of the file).
    std::optional<dist::DrawRequest> onRanks;
    // Set for a frame kept in data units (a slab of a sweep stored as DICOM): RenderResult::values, no
    // display pass. Not on the ranks.
    bool values = false;
    // Who asked (a remote address): the render thread takes turns between owners, so that one address's
    // many requests or viewers do not hold back another's one. Empty: the server's own (warm-ups).
    std::string owner;
    // A newer job of the same client (params.client, not empty) gives this one up between the bands of its
    // walk (or runs of its splat) once it has begun, not only while it waits: a viewer's full-size still
    // that the camera has left holds the render thread for a band, not the whole frame, and the still
    // that ends a drag does not wait for the draft it replaces (render::RenderOptions::abandoned).
    bool abandonable = false;
};

struct RenderResult {
    render::RgbaImage image;   // encoded to PNG by the waiting handler, so the render thread only renders
    render::FloatImage values; // RenderJob::values: the frame in data units instead of `image`
    std::array<float, 2> drawable{0, 0}; // RenderJob::values: every value the renderer can draw
    double frameMs = 0.0;                // render + display pass, without PNG encoding
    double uploadMs = 0.0; // of frameMs: the upload of a Vot-Space or volume not drawn just before (else 0)
    std::size_t votCount = 0; // Vots in the Vot-Space drawn (0 for reference); under mpirun, all ranks'
    double fitMs = 0.0; // under mpirun: the slowest rank's fit the frame was drawn from (made now or before)
};

/// Thread-safe. If no EGL context can be made, every render() gives HttpError 503.
class RenderQueue {
public:
    /// Starts the thread and waits until it has (or has failed to get) a context. Jobs drawn on the ranks
    /// go through `ranks`, which must then outlive the queue.
    /// twoUploadedMaxVots: see holdsBoth.
    RenderQueue(ServerStats& stats, ForegroundActivity& foreground, dist::FrameRanks* ranks = nullptr,
                std::size_t maxWaiting = 64, std::size_t twoUploadedMaxVots = TWO_UPLOADED_MAX_VOTS);
    ~RenderQueue(); // answers waiting jobs with 503 and joins

    RenderQueue(const RenderQueue&) = delete;
    RenderQueue& operator=(const RenderQueue&) = delete;

    bool hasContext() const { return mHasContext; }
    const std::string& contextError() const { return mContextError; }
    const std::string& rendererName() const { return mRendererName; }
    /// "compute" or "fragment": the shader stage the Vot walk runs in (VotRenderer::WalkShader).
    const std::string& walkShaderName() const { return mWalkShaderName; }
    /// What draws the MIP asked for ("splat" on a CPU rasteriser, "walk" on a GPU; VotRenderer::Strategy).
    const std::string& mipStrategyName() const { return mMipStrategyName; }

    /// Queues a job and waits for it. Throws HttpError 409 ("superseded") when a newer job with the
    /// same non-empty client id arrived while this one waited (or, for an abandonable job, while it was
    /// drawn), 503 without a context or when the queue is full, 400 for input the renderer refuses.
    RenderResult render(RenderJob job);
    /// Queues a job whose result nobody waits for (it uploads what it draws). Throws as render() does
    /// before the job is queued.
    void post(RenderJob job) { (void)submit(std::move(job)); }
    std::size_t waiting() const;

    /// The render thread keeps two Vot-Spaces uploaded (a viewer's still at eps and its drafts from the
    /// draft rung), but only while they have at most TWO_UPLOADED_MAX_VOTS together: each uploaded one
    /// costs its renderer's copies (the splat's, the GL buffers) on top of the Vot-Space it keeps alive,
    /// about 0.5 KB a Vot in all, so two of a large study would double what the server holds.
    bool holdsBoth(std::size_t votsA, std::size_t votsB) const {
        return votsA + votsB <= mTwoUploadedMaxVots;
    }
    static constexpr std::size_t TWO_UPLOADED_MAX_VOTS = 4'000'000;

private:
    // A refused job travels back as a value, and render() throws a fresh HttpError on the waiting
    // thread: an exception object shared across threads through a future is freed by whichever thread
    // drops the last reference, and that count lives in libstdc++, where ThreadSanitizer cannot see
    // the ordering (it reported the free racing the waiting thread's read of what()).
    struct Refusal {
        int status = 500;
        std::string message;
    };
    using Outcome = std::variant<RenderResult, Refusal>;
    struct Item {
        RenderJob job;
        std::promise<Outcome> promise;
    };
    std::future<Outcome> submit(RenderJob job);
    /// The answer to a job its client replaced by a newer one, counted in the stats.
    Refusal superseded();
    /// The next item to draw: the oldest of the owner served longest ago (round-robin between owners).
    Item takeNextLocked();
    struct Renderers; // VotRenderer + GridRenderer + what they hold, render thread only
    void threadMain();
    RenderResult draw(Renderers& renderers, const RenderJob& job);

    ServerStats& mStats;
    ForegroundActivity& mForeground;
    dist::FrameRanks* const mRanks;
    const std::size_t mMaxWaiting;
    const std::size_t mTwoUploadedMaxVots;
    mutable std::mutex mMutex;
    std::condition_variable mWake;
    std::deque<Item> mQueue;
    OwnerTurns mTurns;                        // which waiting job is next
    std::string mAbandonableClient;           // the client of the job being drawn, when it is abandonable
    std::atomic<bool> mAbandonDrawing{false}; // that client has asked for another frame (or the queue stops)
    bool mStopping = false;
    bool mReady = false;
    bool mHasContext = false;
    std::string mContextError;
    std::string mRendererName;
    std::string mWalkShaderName;
    std::string mMipStrategyName;
    std::thread mThread;
};

} // namespace vots::server
