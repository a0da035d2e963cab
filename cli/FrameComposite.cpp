// FrameComposite: max, min and length-weighted mean of the ranks' float frames, one rank at a time, with
// the arithmetic of the collective composite (DistributedRender.h).
#include "FrameComposite.h"

#include "DistributedRender.h"

#include <algorithm>
#include <stdexcept>

namespace vots::cli {

FrameComposite::FrameComposite(render::RenderMode mode, SlabFrame first)
    : mMode(mode), mFromGrid(first.fromGrid) {
    if (mode == render::RenderMode::Density && !first.displayRange)
        throw std::logic_error("FrameComposite: a density frame without its range");
    mDisplayRange = first.displayRange;
    mFrame = std::move(first.frame);
    if (mode == render::RenderMode::Aip && mFromGrid) {
        // Summed in double, as compositeGridOnRoot sums: two ranks' parts round once.
        mSums.assign(mFrame.pixels.begin(), mFrame.pixels.end());
        return;
    }
    if (mode == render::RenderMode::MinIp && !mFromGrid) minIpForCombining(mFrame.pixels);
    if (mode == render::RenderMode::Aip) {
        if (!first.lengths) throw std::logic_error("FrameComposite: an aip frame without its lengths");
        mSums.assign(2 * mFrame.pixels.size(), 0.0);
        addMeanParts(mSums, mFrame, *first.lengths);
    }
}

void FrameComposite::add(const SlabFrame& other) {
    if (other.frame.width != mFrame.width || other.frame.height != mFrame.height)
        throw std::runtime_error("a rank's frame has another size");
    if (other.fromGrid != mFromGrid) throw std::runtime_error("a rank drew the frame with another renderer");
    if (other.displayRange.has_value() != mDisplayRange.has_value())
        throw std::runtime_error("a rank's frame came with another window");
    if (mDisplayRange)
        *mDisplayRange = {std::min((*mDisplayRange)[0], (*other.displayRange)[0]),
                          std::max((*mDisplayRange)[1], (*other.displayRange)[1])};
    switch (mMode) {
    case render::RenderMode::Mip:
        combineExtremes(mMode, mFrame.pixels, other.frame.pixels);
        return;
    case render::RenderMode::MinIp: {
        if (mFromGrid) { // +inf where a rank's ray takes nothing, as compositeGridOnRoot's min
            combineExtremes(mMode, mFrame.pixels, other.frame.pixels);
            return;
        }
        std::vector<float> theirs = other.frame.pixels;
        minIpForCombining(theirs);
        combineExtremes(mMode, mFrame.pixels, theirs);
        return;
    }
    case render::RenderMode::Aip:
        if (mFromGrid) {
            for (std::size_t i = 0; i < mSums.size(); ++i)
                mSums[i] += other.frame.pixels[i];
            return;
        }
        if (!other.lengths) throw std::runtime_error("a rank's aip frame came without its lengths");
        addMeanParts(mSums, other.frame, *other.lengths);
        return;
    case render::RenderMode::Density:
        combineExtremes(mMode, mFrame.pixels, other.frame.pixels); // the smaller box; +inf where none
        return;
    }
    throw std::logic_error("FrameComposite: unsupported mode");
}

render::FloatImage FrameComposite::finish() {
    if (mMode == render::RenderMode::Aip && mFromGrid) {
        for (std::size_t i = 0; i < mSums.size(); ++i)
            mFrame.pixels[i] = static_cast<float>(mSums[i]);
        return std::move(mFrame);
    }
    if (mMode == render::RenderMode::MinIp) minIpFromCombined(mFrame.pixels);
    if (mMode == render::RenderMode::Aip) meansFromParts(mSums, mFrame);
    return std::move(mFrame);
}

} // namespace vots::cli
