// DraftSizer: pixels per budget from a smoothed time per pixel.
#include "stream/DraftSizer.h"

#include <algorithm>
#include <cmath>

namespace vots::server {
namespace {

constexpr double SMOOTHING = 1.0 / 3.0; // weight of the newest measurement

} // namespace

std::pair<int, int> DraftSizer::draftSize(int fullWidth, int fullHeight) const {
    const double fullPixels = static_cast<double>(fullWidth) * fullHeight;
    double scale = FIRST_SCALE;
    if (mMsPerPixel && *mMsPerPixel > 0) scale = std::sqrt(mBudgetMs / *mMsPerPixel / fullPixels);
    scale = std::clamp(scale, MIN_SCALE, 1.0);
    const auto side = [scale](int full) { return std::max(1, static_cast<int>(std::lround(full * scale))); };
    return {side(fullWidth), side(fullHeight)};
}

bool DraftSizer::fullSizeWithin(int fullWidth, int fullHeight, double margin) const {
    return mMsPerPixel && *mMsPerPixel * fullWidth * fullHeight * margin <= mBudgetMs;
}

bool draftFromRung(const DraftSizer& atEps, const DraftSizer& atRung, int fullWidth, int fullHeight) {
    if (atEps.measured()) return !atEps.fullSizeWithin(fullWidth, fullHeight);
    return !atRung.fullSizeWithin(fullWidth, fullHeight, RUNG_GAIN);
}

void DraftSizer::observe(int width, int height, double ms) {
    const double pixels = static_cast<double>(width) * height;
    if (pixels <= 0 || !std::isfinite(ms) || ms < 0) return;
    const double perPixel = ms / pixels;
    mMsPerPixel = mMsPerPixel ? *mMsPerPixel + SMOOTHING * (perPixel - *mMsPerPixel) : perPixel;
}

} // namespace vots::server
