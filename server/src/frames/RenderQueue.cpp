// RenderQueue: the render thread owns the GL context; a newer frame of a client replaces its waiting one.
#include "frames/RenderQueue.h"

#include "HttpError.h"
#include "ServerStats.h"
#include "frames/ForegroundActivity.h"
#include "routes/HttpJson.h"
#include "vots/fit/Error.h"
#include "vots/render/EglContext.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/RenderPolicy.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <iostream>
#include <stdexcept>
#include <tuple>

namespace vots::server {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

/// Everything GL lives here and is created, used and destroyed on the render thread only.
/// Members are destroyed bottom-up, so the context outlives the renderers.
struct RenderQueue::Renderers {
    /// A Vot renderer and the Vot-Space uploaded to it.
    struct VotSlot {
        std::unique_ptr<render::VotRenderer> renderer; // made on first use (slot 0's at start)
        std::shared_ptr<const fit::VotSpace> space;    // kept alive so the pointer compare is sound
        std::uint64_t lastUse = 0;
    };
    std::unique_ptr<render::EglContext> context;
    // Two, since a viewer's drafts are drawn from a coarser fit than its still (draftRung): with one the
    // still after every drag, and the drag's first draft, would wait for an upload (74 ms for the
    // splat's copy of 170 k Vots). The least recently used slot takes a Vot-Space that neither holds.
    std::array<VotSlot, 2> votSlots;
    std::uint64_t votUses = 0;
    std::unique_ptr<render::GridRenderer> grid;
    std::shared_ptr<const fit::Volume> uploadedVolume;

    /// Slot 0's renderer: the one the ranks draw with, and whose strategy /api/stats names.
    render::VotRenderer& vots() { return rendererOf(votSlots[0]); }
    static render::VotRenderer& rendererOf(VotSlot& slot) {
        if (!slot.renderer) {
            slot.renderer = std::make_unique<render::VotRenderer>();
            applyRenderPolicy(*slot.renderer);
        }
        return *slot.renderer;
    }
    /// The renderer holding `space`, uploading it (to the least recently used slot) when none does.
    /// Returns whether it uploaded.
    std::pair<render::VotRenderer*, bool> votsFor(const std::shared_ptr<const fit::VotSpace>& space,
                                                  const RenderQueue& queue) {
        auto slot = std::find_if(votSlots.begin(), votSlots.end(),
                                 [&](const VotSlot& held) { return held.space == space; });
        if (slot == votSlots.end())
            slot = std::min_element(votSlots.begin(), votSlots.end(),
                                    [](const VotSlot& a, const VotSlot& b) { return a.lastUse < b.lastUse; });
        slot->lastUse = ++votUses;
        const bool upload = slot->space != space;
        if (upload) {
            // Two large Vot-Spaces are not held at once: the other is let go first (renderer and all).
            for (VotSlot& other : votSlots)
                if (&other != &*slot && other.space &&
                    !queue.holdsBoth(other.space->vots.size(), space->vots.size())) {
                    other.renderer.reset();
                    other.space.reset();
                }
            rendererOf(*slot).upload(*space);
            slot->space = space;
        }
        return {slot->renderer.get(), upload};
    }
};

RenderQueue::RenderQueue(ServerStats& stats, ForegroundActivity& foreground, dist::FrameRanks* ranks,
                         std::size_t maxWaiting, std::size_t twoUploadedMaxVots)
    : mStats(stats), mForeground(foreground), mRanks(ranks), mMaxWaiting(maxWaiting),
      mTwoUploadedMaxVots(twoUploadedMaxVots) {
    mThread = std::thread([this] { threadMain(); });
    std::unique_lock lock(mMutex);
    mWake.wait(lock, [this] { return mReady; });
}

RenderQueue::~RenderQueue() {
    {
        std::lock_guard lock(mMutex);
        mStopping = true;
    }
    mAbandonDrawing.store(true, std::memory_order_relaxed); // a long still need not hold the stop
    mWake.notify_all();
    mThread.join();
    for (Item& item : mQueue) // left by a thread that had no context, or by the stop
        item.promise.set_value(Refusal{503, "server is stopping"});
}

std::size_t RenderQueue::waiting() const {
    std::lock_guard lock(mMutex);
    return mQueue.size();
}

RenderResult RenderQueue::render(RenderJob job) {
    Outcome outcome = submit(std::move(job)).get();
    if (auto* refusal = std::get_if<Refusal>(&outcome)) throw HttpError(refusal->status, refusal->message);
    return std::move(std::get<RenderResult>(outcome));
}

std::future<RenderQueue::Outcome> RenderQueue::submit(RenderJob job) {
    Item item{std::move(job), {}};
    auto future = item.promise.get_future();
    std::lock_guard lock(mMutex);
    if (!mHasContext) throw HttpError(503, "rendering is unavailable: " + mContextError);
    if (mStopping) throw HttpError(503, "server is stopping");
    const std::string& client = item.job.params.client;
    auto replaced = mQueue.end();
    if (!client.empty()) {
        // The client has moved on: it wants this newer frame, not the one still waiting (at most one
        // waits per client, since each arrival replaces the previous).
        replaced = std::find_if(mQueue.begin(), mQueue.end(),
                                [&](const Item& queued) { return queued.job.params.client == client; });
        if (replaced != mQueue.end()) replaced->promise.set_value(superseded());
    }
    if (replaced == mQueue.end() && mQueue.size() >= mMaxWaiting)
        throw HttpError(503, "render queue is full; try again");
    // The client has moved on from the frame being drawn too, when it may be given up.
    if (!client.empty() && client == mAbandonableClient)
        mAbandonDrawing.store(true, std::memory_order_relaxed);
    // The newer frame takes the replaced one's place: at the back, a client that replaces its frame more
    // often than the queue turns over (a viewer's paused drag asking for its still, then moving on,
    // behind seven other viewers' drafts) was never drawn (bench/RESULTS.md, "Eight viewers in one
    // browser").
    if (replaced != mQueue.end())
        *replaced = std::move(item);
    else
        mQueue.push_back(std::move(item));
    mWake.notify_one();
    return future;
}

RenderQueue::Refusal RenderQueue::superseded() {
    mStats.addSuperseded();
    return Refusal{409, "superseded"};
}

void RenderQueue::threadMain() {
    Renderers renderers;
    std::string error;
    try {
        renderers.context = render::EglContext::create(&error);
        if (renderers.context) {
            (void)renderers.vots(); // made now: a renderer that fails here leaves the server without one
            renderers.grid = std::make_unique<render::GridRenderer>();
        }
    } catch (const std::exception& e) { // a shader that does not compile on this driver, say
        error = e.what();
        renderers = Renderers{};
    }
    {
        std::lock_guard lock(mMutex);
        mHasContext = renderers.context != nullptr;
        mContextError = mHasContext ? "" : (error.empty() ? "no EGL context" : error);
        mRendererName = mHasContext ? renderers.context->renderer() : "";
        if (mHasContext) {
            mWalkShaderName = render::walkShaderName(renderers.vots().walkShader());
            mMipStrategyName = render::strategyName(renderers.vots().strategy());
        }
        mReady = true;
    }
    mWake.notify_all();
    if (!mHasContext) {
        std::cerr << "vots serve: warning: no renderer, /render answers 503: " << mContextError << "\n";
        return;
    }

    for (;;) {
        Item item;
        {
            std::unique_lock lock(mMutex);
            mWake.wait(lock, [this] { return mStopping || !mQueue.empty(); });
            if (mStopping) return;
            item = takeNextLocked();
            mAbandonableClient = item.job.abandonable ? item.job.params.client : "";
            mAbandonDrawing.store(false, std::memory_order_relaxed);
        }
        Outcome outcome;
        try {
            outcome = draw(renderers, item.job);
        } catch (const render::FrameAbandoned&) {
            outcome = superseded();
        } catch (...) {
            HttpFailure failure = httpFailureOf(std::current_exception(), "render failed");
            outcome = Refusal{failure.status, std::move(failure.message)};
        }
        {
            std::lock_guard lock(mMutex);
            mAbandonableClient.clear();
        }
        item.promise.set_value(std::move(outcome));
    }
}

RenderQueue::Item RenderQueue::takeNextLocked() {
    const auto ownersWaiting = [this] {
        std::vector<std::string_view> owners;
        owners.reserve(mQueue.size());
        for (const Item& queued : mQueue)
            owners.push_back(queued.job.owner);
        return owners;
    };
    const auto pick = mQueue.begin() + static_cast<std::ptrdiff_t>(mTurns.pick(ownersWaiting()));
    Item item = std::move(*pick);
    mQueue.erase(pick);
    mTurns.served(item.job.owner, ownersWaiting());
    return item;
}

RenderResult RenderQueue::draw(Renderers& r, const RenderJob& job) {
    const RenderParams& p = job.params;
    RenderResult result;
    const ForegroundMark mark(mForeground, Foreground::Frame); // warm-ups and cache files wait meanwhile
    const auto start = std::chrono::steady_clock::now();
    if (job.onRanks) {
        if (job.values) throw std::logic_error("a frame in data units on the ranks");
        if (!mRanks) throw std::logic_error("a frame on the ranks on a queue without them");
        dist::DrawRequest request = *job.onRanks;
        request.frame = p;
        r.votSlots[0].space = nullptr; // the ranks' port uploads this rank's own Vots and samples
        r.uploadedVolume = nullptr;
        const dist::ComposedFrame composed = mRanks->draw(request, r.vots(), *r.grid);
        // Shown as one process shows its frame: the same display pass over the same range.
        result.image = render::applyDisplay(composed.image, render::displayFor(p, composed.displayRange));
        // Read here, on the render thread, before another frame replaces them.
        for (const dist::RankTimes& t : mRanks->lastTimes()) {
            result.votCount += static_cast<std::size_t>(t.votCount);
            result.fitMs = std::max(result.fitMs, t.heldFitMs);
        }
        // A file's Vot crossing the face between two ranks' cells is drawn by both (minip, aip) but is one
        // Vot.
        if (job.space) result.votCount = job.space->vots.size();
        result.frameMs = msSince(start);
        mStats.addFrame(result.frameMs);
        return result;
    }
    render::VotRenderer* vots = nullptr;
    if (p.renderer == render::RendererKind::Grid) {
        if (r.uploadedVolume != job.volume) {
            r.grid->upload(*job.volume);
            r.uploadedVolume = job.volume;
            result.uploadMs = msSince(start);
        }
    } else {
        bool uploaded = false;
        std::tie(vots, uploaded) = r.votsFor(job.space, *this);
        if (uploaded) result.uploadMs = msSince(start);
        result.votCount = job.space->vots.size();
    }
    if (job.values) {
        render::Renderer& renderer =
            p.renderer == render::RendererKind::Grid ? static_cast<render::Renderer&>(*r.grid) : *vots;
        result.values = renderer.render(p.camera, p.width, p.height, render::RenderOptions{p.mode, p.slab});
        result.drawable = renderer.valueRange();
    } else {
        const auto abandoned = [this] { return mAbandonDrawing.load(std::memory_order_relaxed); };
        result.image = render::renderFrame(p, vots, r.grid.get(), job.valueRange,
                                           job.abandonable ? std::function<bool()>(abandoned) : nullptr);
    }
    result.frameMs = msSince(start);
    mStats.addFrame(result.frameMs);
    return result;
}

} // namespace vots::server
