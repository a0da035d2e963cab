// CPU min-pyramid over a max image: the smallest current max within any pixel rectangle, in O(1).
#pragma once

#include <vector>

namespace vots::render {

/// Built from the R32F max image between culling batches (rows bottom-up, as GL reads them).
/// Level 0 holds the minimum of each 8x8 pixel tile; each level above halves both sides.
class MaxPyramid {
public:
    void build(const float* pixels, int width, int height);
    /// Minimum of the max image over pixels [x0, x1] x [y0, y1] (inclusive, clamped by the caller),
    /// possibly over a slightly larger area (still a valid lower bound for the rectangle).
    float minOver(int x0, int y0, int x1, int y1) const;

private:
    struct Level {
        int width = 0;
        int height = 0;
        std::vector<float> mins;
    };
    std::vector<Level> mLevels;
};

} // namespace vots::render
