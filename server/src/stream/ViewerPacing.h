// Which view a viewer's socket draws next: the latest camera only, and no more frames in flight than the
// page has acknowledged room for (as Selkies paces by acknowledgements, so no queue builds up anywhere).
#pragma once

#include "routes/Params.h"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace vots::server {

/// A view the page asked for, parsed.
struct PendingView {
    std::uint64_t seq = 0;
    bool still = false;
    RenderParams params;
    std::chrono::steady_clock::time_point arrived; // when the page's message came (a frame's waitMs)
};

/// Not thread-safe: its viewer locks around it. "In flight": the frames being drawn plus the frames
/// sent and not yet acknowledged. At most one draft is rendered at a time, and the next may start as soon
/// as the last one's render is done, while that one is still encoded and sent: the render thread goes on
/// to the next draft instead of waiting for a JPEG. At most two stills are drawn at a time: a still never
/// waits behind a draft or an older still (the page waits for the newest still alone; the older one is
/// dropped from the render queue when it has not begun there), and a draft may start while an older
/// still draws (it queues behind it on the render thread, so the drag goes on as soon as that is out).
class ViewerPacing {
public:
    explicit ViewerPacing(std::size_t maxInFlight) : mMaxInFlight(maxInFlight) {}

    /// The page's newest view; replaces one that was waiting (counted in dropped()).
    void offer(PendingView view);
    /// The view to draw now, or none: nothing waits, as many of its kind are being drawn as may be, or
    /// (for a draft) the page has not acknowledged enough. A view taken is being drawn until sent() or
    /// failed().
    std::optional<PendingView> next();
    /// The draft `drawn` has been rendered (its image is being encoded): the next draft may be taken.
    void rendered(const PendingView& drawn);
    /// The view `drawn` is ready: its frame number (1, 2, ...) to send it under; none when a newer view's
    /// frame has gone out meanwhile, so this one shows an old camera (dropped, counted in dropped()).
    std::optional<std::uint64_t> sent(const PendingView& drawn);
    /// The view `drawn` gave no frame (an error answer went out instead, or none).
    void failed(const PendingView& drawn);
    /// The page has shown every frame up to `frame`; false for a frame not sent yet (a broken page).
    bool acknowledge(std::uint64_t frame);
    /// Whether a newer view than `drawn` has been taken (a still after a draft, a draft after a still): a
    /// frame not drawn yet is then not worth drawing.
    bool overtaken(const PendingView& drawn) const { return mNewestTaken > drawn.seq; }

    std::size_t inFlight() const {
        return (mRenderingDraft ? 1 : 0) + mEncodingDrafts + mStillsDrawing +
               static_cast<std::size_t>(mSent - mAcked);
    }
    std::size_t dropped() const { return mDropped; }
    bool drawingStill() const { return mStillsDrawing > 0; }

    static constexpr std::size_t MAX_STILLS_DRAWING = 2;

private:
    void doneDrawing(const PendingView& drawn) {
        if (drawn.still)
            --mStillsDrawing;
        else if (mRenderingDraft == drawn.seq)
            mRenderingDraft.reset();
        else
            --mEncodingDrafts;
    }

    const std::size_t mMaxInFlight;
    std::optional<PendingView> mWaiting;
    std::optional<std::uint64_t> mRenderingDraft; // the seq of the draft taken and not yet rendered
    std::size_t mEncodingDrafts = 0;              // drafts rendered, not yet sent or failed
    std::size_t mStillsDrawing = 0;
    std::uint64_t mNewestTaken = 0;   // the seq of the newest view taken
    std::uint64_t mNewestSentSeq = 0; // the seq of the newest view whose frame went out
    std::uint64_t mSent = 0;          // frames sent so far (the last one's number)
    std::uint64_t mAcked = 0;         // highest frame acknowledged
    std::size_t mDropped = 0;
};

} // namespace vots::server
