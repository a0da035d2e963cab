// FrameComposite: max, min and length-weighted mean of the ranks' float frames, one rank at a time.
#include "FrameComposite.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vots::cli {
namespace {

void addMeans(std::vector<double>& sums, const render::FloatImage& means, const render::FloatImage& lengths) {
    const std::size_t count = means.pixels.size();
    if (lengths.pixels.size() != count || sums.size() != 2 * count)
        throw std::runtime_error("a rank's aip frame has another size");
    for (std::size_t i = 0; i < count; ++i) {
        const float mean = means.pixels[i], length = lengths.pixels[i];
        if (!std::isfinite(mean) || !(length > 0.f)) continue; // this rank's ray misses its cells
        sums[i] += double(mean) * double(length);
        sums[count + i] += double(length);
    }
}

} // namespace

FrameComposite::FrameComposite(render::RenderMode mode, SlabFrame first) : mMode(mode) {
    if (mode == render::RenderMode::Density)
        throw std::logic_error("FrameComposite: the density is not composited across ranks here");
    mFrame = std::move(first.frame);
    if (mode == render::RenderMode::MinIp)
        for (float& v : mFrame.pixels)
            if (v == -INFINITY) v = INFINITY;
    if (mode == render::RenderMode::Aip) {
        if (!first.lengths) throw std::logic_error("FrameComposite: an aip frame without its lengths");
        mSums.assign(2 * mFrame.pixels.size(), 0.0);
        addMeans(mSums, mFrame, *first.lengths);
    }
}

void FrameComposite::add(const SlabFrame& other) {
    const std::vector<float>& theirs = other.frame.pixels;
    if (other.frame.width != mFrame.width || other.frame.height != mFrame.height ||
        theirs.size() != mFrame.pixels.size())
        throw std::runtime_error("a rank's frame has another size");
    switch (mMode) {
    case render::RenderMode::Mip:
        for (std::size_t i = 0; i < theirs.size(); ++i)
            mFrame.pixels[i] = std::max(mFrame.pixels[i], theirs[i]);
        return;
    case render::RenderMode::MinIp:
        for (std::size_t i = 0; i < theirs.size(); ++i)
            if (theirs[i] != -INFINITY) mFrame.pixels[i] = std::min(mFrame.pixels[i], theirs[i]);
        return;
    case render::RenderMode::Aip:
        if (!other.lengths) throw std::runtime_error("a rank's aip frame came without its lengths");
        addMeans(mSums, other.frame, *other.lengths);
        return;
    case render::RenderMode::Density:
        break;
    }
    throw std::logic_error("FrameComposite: unsupported mode");
}

render::FloatImage FrameComposite::finish() {
    const std::size_t count = mFrame.pixels.size();
    if (mMode == render::RenderMode::MinIp)
        for (float& v : mFrame.pixels)
            if (v == INFINITY) v = -INFINITY;
    if (mMode == render::RenderMode::Aip)
        for (std::size_t i = 0; i < count; ++i)
            mFrame.pixels[i] =
                mSums[count + i] > 0.0 ? static_cast<float>(mSums[i] / mSums[count + i]) : -INFINITY;
    return std::move(mFrame);
}

} // namespace vots::cli
