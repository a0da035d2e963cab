// ViewerPacing: latest view wins, frames paced by acknowledgements.
#include "stream/ViewerPacing.h"

namespace vots::server {

void ViewerPacing::offer(PendingView view) {
    if (mWaiting) ++mDropped;
    mWaiting = std::move(view);
}

std::optional<PendingView> ViewerPacing::next() {
    if (!mWaiting || mDrawing) return std::nullopt;
    // A still goes without waiting for acknowledgements: the page waits for it alone, and it is at most
    // one frame more than the limit.
    if (!mWaiting->still && inFlight() >= mMaxInFlight) return std::nullopt;
    std::optional<PendingView> view = std::move(mWaiting);
    mWaiting.reset();
    mDrawing = true;
    return view;
}

std::uint64_t ViewerPacing::sent() {
    mDrawing = false;
    return ++mSent;
}

void ViewerPacing::failed() {
    mDrawing = false;
}

bool ViewerPacing::acknowledge(std::uint64_t frame) {
    if (frame > mSent) return false;
    if (frame > mAcked) mAcked = frame;
    return true;
}

} // namespace vots::server
