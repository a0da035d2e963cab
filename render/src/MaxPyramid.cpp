// Tile-min pyramid construction and rectangle queries for CPU culling.
#include "MaxPyramid.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

namespace {
constexpr int TILE_SHIFT = 3; // 8x8 pixel tiles at level 0
}

void MaxPyramid::build(const float* pixels, int width, int height) {
    mLevels.clear();
    Level base;
    base.width = (width + 7) >> TILE_SHIFT;
    base.height = (height + 7) >> TILE_SHIFT;
    base.mins.assign(static_cast<std::size_t>(base.width) * static_cast<std::size_t>(base.height), INFINITY);
    for (int y = 0; y < height; ++y) {
        const float* row = pixels + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        float* tileRow = base.mins.data() +
                         static_cast<std::size_t>(y >> TILE_SHIFT) * static_cast<std::size_t>(base.width);
        for (int x = 0; x < width; ++x)
            tileRow[x >> TILE_SHIFT] = std::min(tileRow[x >> TILE_SHIFT], row[x]);
    }
    mLevels.push_back(std::move(base));
    while (mLevels.back().width > 1 || mLevels.back().height > 1) {
        const Level& below = mLevels.back();
        Level up;
        up.width = (below.width + 1) / 2;
        up.height = (below.height + 1) / 2;
        up.mins.assign(static_cast<std::size_t>(up.width) * static_cast<std::size_t>(up.height), INFINITY);
        for (int y = 0; y < below.height; ++y)
            for (int x = 0; x < below.width; ++x) {
                float& m =
                    up.mins[static_cast<std::size_t>(y / 2) * up.width + static_cast<std::size_t>(x / 2)];
                m = std::min(
                    m, below.mins[static_cast<std::size_t>(y) * below.width + static_cast<std::size_t>(x)]);
            }
        mLevels.push_back(std::move(up));
    }
}

float MaxPyramid::minOver(int x0, int y0, int x1, int y1) const {
    int shift = TILE_SHIFT;
    std::size_t level = 0;
    // Climb until the rectangle touches at most 2 x 2 cells.
    while (level + 1 < mLevels.size() &&
           ((x1 >> shift) - (x0 >> shift) > 1 || (y1 >> shift) - (y0 >> shift) > 1)) {
        ++level;
        ++shift;
    }
    const Level& l = mLevels[level];
    float m = INFINITY;
    for (int y = y0 >> shift; y <= std::min(y1 >> shift, l.height - 1); ++y)
        for (int x = x0 >> shift; x <= std::min(x1 >> shift, l.width - 1); ++x)
            m = std::min(m, l.mins[static_cast<std::size_t>(y) * l.width + static_cast<std::size_t>(x)]);
    return m;
}

} // namespace vots::render
