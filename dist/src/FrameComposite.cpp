// FrameComposite: the ranks' float frames combined one at a time by the composite table's operation.
#include "vots/dist/FrameComposite.h"

#include <algorithm>
#include <stdexcept>

namespace vots::dist {

FrameComposite::FrameComposite(render::RenderMode mode, RankFrame first)
    : mOp(compositeOpFor(mode, first.source)), mSource(first.source) {
    if (mode == render::RenderMode::Density && !first.displayRange)
        throw std::logic_error("FrameComposite: a density frame without its range");
    mDisplayRange = first.displayRange;
    mFrame = std::move(first.frame);
    switch (mOp) {
    case CompositeOp::Max:
    case CompositeOp::Min:
        return;
    case CompositeOp::MinOfCutRays:
        minOfCutRaysForCombining(mFrame.pixels);
        return;
    case CompositeOp::WeightedMean:
        if (!first.lengths) throw std::logic_error("FrameComposite: an aip frame without its lengths");
        mSums.assign(2 * mFrame.pixels.size(), 0.0);
        addMeanParts(mSums, mFrame, *first.lengths);
        return;
    case CompositeOp::Sum:
        mSums.assign(mFrame.pixels.size(), 0.0);
        addSumPart(mSums, mFrame.pixels);
        return;
    }
}

void FrameComposite::add(const RankFrame& other) {
    if (other.frame.width != mFrame.width || other.frame.height != mFrame.height)
        throw std::runtime_error("a rank's frame has another size");
    if (other.source != mSource) throw std::runtime_error("a rank drew the frame with another renderer");
    if (other.displayRange.has_value() != mDisplayRange.has_value())
        throw std::runtime_error("a rank's frame came with another window");
    if (mDisplayRange)
        *mDisplayRange = {std::min((*mDisplayRange)[0], (*other.displayRange)[0]),
                          std::max((*mDisplayRange)[1], (*other.displayRange)[1])};
    switch (mOp) {
    case CompositeOp::Max:
    case CompositeOp::Min:
        combineExtremes(mOp, mFrame.pixels, other.frame.pixels);
        return;
    case CompositeOp::MinOfCutRays: {
        std::vector<float> theirs = other.frame.pixels;
        minOfCutRaysForCombining(theirs);
        combineExtremes(mOp, mFrame.pixels, theirs);
        return;
    }
    case CompositeOp::WeightedMean:
        if (!other.lengths) throw std::runtime_error("a rank's aip frame came without its lengths");
        addMeanParts(mSums, other.frame, *other.lengths);
        return;
    case CompositeOp::Sum:
        addSumPart(mSums, other.frame.pixels);
        return;
    }
}

render::FloatImage FrameComposite::finish() {
    switch (mOp) {
    case CompositeOp::Max:
    case CompositeOp::Min:
        break;
    case CompositeOp::MinOfCutRays:
        minOfCutRaysFromCombined(mFrame.pixels);
        break;
    case CompositeOp::WeightedMean:
        meansFromParts(mSums, mFrame);
        break;
    case CompositeOp::Sum:
        sumsToFrame(mSums, mFrame);
        break;
    }
    return std::move(mFrame);
}

} // namespace vots::dist
