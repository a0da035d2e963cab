// Which view a viewer's socket draws next: the latest camera only, and no more frames in flight than the
// page has acknowledged room for (as Selkies paces by acknowledgements, so no queue builds up anywhere).
#pragma once

#include "routes/Params.h"

#include <cstddef>
#include <cstdint>
#include <optional>

namespace vots::server {

/// A view the page asked for, parsed.
struct PendingView {
    std::uint64_t seq = 0;
    bool still = false;
    RenderParams params;
};

/// Not thread-safe: its viewer locks around it. "In flight": the frame being drawn plus the frames
/// sent and not yet acknowledged.
class ViewerPacing {
public:
    explicit ViewerPacing(std::size_t maxInFlight) : mMaxInFlight(maxInFlight) {}

    /// The page's newest view; replaces one that was waiting (counted in dropped()).
    void offer(PendingView view);
    /// The view to draw now, or none: nothing waits, one is being drawn, or (for a draft) the page has
    /// not acknowledged enough. A view taken is being drawn until sent() or failed().
    std::optional<PendingView> next();
    /// The view being drawn went out as a frame: its number (1, 2, ...).
    std::uint64_t sent();
    /// The view being drawn gave no frame (an error answer went out instead).
    void failed();
    /// The page has shown every frame up to `frame`; false for a frame not sent yet (a broken page).
    bool acknowledge(std::uint64_t frame);

    std::size_t inFlight() const { return (mDrawing ? 1 : 0) + static_cast<std::size_t>(mSent - mAcked); }
    std::size_t dropped() const { return mDropped; }

private:
    const std::size_t mMaxInFlight;
    std::optional<PendingView> mWaiting;
    bool mDrawing = false;
    std::uint64_t mSent = 0;  // frames sent so far (the last one's number)
    std::uint64_t mAcked = 0; // highest frame acknowledged
    std::size_t mDropped = 0;
};

} // namespace vots::server
