// FrameComposite: max, min and length-weighted mean of the ranks' float frames, one rank at a time, with
// the arithmetic of the collective composite (DistributedRender.h).
#include "FrameComposite.h"

#include "DistributedRender.h"

#include <stdexcept>

namespace vots::cli {

FrameComposite::FrameComposite(render::RenderMode mode, SlabFrame first) : mMode(mode) {
    if (mode == render::RenderMode::Density)
        throw std::logic_error("FrameComposite: the density is not composited across ranks here");
    mFrame = std::move(first.frame);
    if (mode == render::RenderMode::MinIp) minIpForCombining(mFrame.pixels);
    if (mode == render::RenderMode::Aip) {
        if (!first.lengths) throw std::logic_error("FrameComposite: an aip frame without its lengths");
        mSums.assign(2 * mFrame.pixels.size(), 0.0);
        addMeanParts(mSums, mFrame, *first.lengths);
    }
}

void FrameComposite::add(const SlabFrame& other) {
    if (other.frame.width != mFrame.width || other.frame.height != mFrame.height)
        throw std::runtime_error("a rank's frame has another size");
    switch (mMode) {
    case render::RenderMode::Mip:
        combineExtremes(mMode, mFrame.pixels, other.frame.pixels);
        return;
    case render::RenderMode::MinIp: {
        std::vector<float> theirs = other.frame.pixels;
        minIpForCombining(theirs);
        combineExtremes(mMode, mFrame.pixels, theirs);
        return;
    }
    case render::RenderMode::Aip:
        if (!other.lengths) throw std::runtime_error("a rank's aip frame came without its lengths");
        addMeanParts(mSums, other.frame, *other.lengths);
        return;
    case render::RenderMode::Density:
        break;
    }
    throw std::logic_error("FrameComposite: unsupported mode");
}

render::FloatImage FrameComposite::finish() {
    if (mMode == render::RenderMode::MinIp) minIpFromCombined(mFrame.pixels);
    if (mMode == render::RenderMode::Aip) meansFromParts(mSums, mFrame);
    return std::move(mFrame);
}

} // namespace vots::cli
