// Per-brick bounds on everything a view's rays can still meet, so the walk can stop a ray early.
#pragma once

#include <array>
#include <vector>

namespace vots::render {

/// The rays of one view in grid index space: parallel (orthographic) or through one eye (perspective).
struct RayFamily {
    bool parallel = true;
    std::array<double, 3> direction{0, 0, 1}; // parallel: the rays' direction, any length
    std::array<double, 3> eye{0, 0, 0};       // perspective: the point every ray starts from
};

/// The rays of the view whose inverse view-projection (clip -> index space) is clipToIndex.
RayFamily rayFamilyOf(const std::array<double, 16>& clipToIndex);

/// The brick layout the walk reads (VotWalkGrid.h): cells per axis, bricks per axis, brick side.
struct BrickLayout {
    std::array<int, 3> cells{0, 0, 0};
    std::array<int, 3> bricks{0, 0, 0};
    int brickShift = 4;
};

/// For every brick B (x fastest): an upper bound of brickMax over every brick that a ray of the family
/// can reach after any point of B (B included), or +inf where the family spreads too wide for a
/// useful bound (an eye inside or beside B). Once a pixel's max reaches it, nothing further along the
/// ray can raise the max, and the walk may stop. Rays are taken in tubes about a brick wide, slab by
/// slab from the far end, widened by half a cell so float rounding in the walk cannot step outside
/// them: linear in the bricks, and at most a tube looser than the exact beam (docs/DESIGN.md §6).
std::vector<float> brickMaximaAhead(const BrickLayout& layout, const std::vector<float>& brickMax,
                                    const RayFamily& rays);

} // namespace vots::render
