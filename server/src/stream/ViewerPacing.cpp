// ViewerPacing: latest view wins, frames paced by acknowledgements, a still never behind a draft.
#include "stream/ViewerPacing.h"

namespace vots::server {

void ViewerPacing::offer(PendingView view) {
    if (mWaiting) ++mDropped;
    mWaiting = std::move(view);
}

std::optional<PendingView> ViewerPacing::next() {
    if (!mWaiting) return std::nullopt;
    if (mWaiting->still) {
        // Without waiting for acknowledgements or the draft being drawn: the page waits for this frame
        // alone, and it is at most one frame more than the limit.
        if (mStillsDrawing >= MAX_STILLS_DRAWING) return std::nullopt;
        ++mStillsDrawing;
    } else {
        if (mRenderingDraft || inFlight() >= mMaxInFlight) return std::nullopt;
        mRenderingDraft = mWaiting->seq;
    }
    if (mWaiting->seq > mNewestTaken) mNewestTaken = mWaiting->seq;
    std::optional<PendingView> view = std::move(mWaiting);
    mWaiting.reset();
    return view;
}

void ViewerPacing::rendered(const PendingView& drawn) {
    if (drawn.still || mRenderingDraft != drawn.seq) return;
    mRenderingDraft.reset();
    ++mEncodingDrafts;
}

std::optional<std::uint64_t> ViewerPacing::sent(const PendingView& drawn) {
    doneDrawing(drawn);
    if (drawn.seq < mNewestSentSeq) {
        ++mDropped;
        return std::nullopt;
    }
    mNewestSentSeq = drawn.seq;
    return ++mSent;
}

void ViewerPacing::failed(const PendingView& drawn) {
    doneDrawing(drawn);
}

bool ViewerPacing::acknowledge(std::uint64_t frame) {
    if (frame > mSent) return false;
    if (frame > mAcked) mAcked = frame;
    return true;
}

} // namespace vots::server
