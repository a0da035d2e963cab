// Cell -> Vot index grid and per-brick bound maxima for the Walk MIP strategy (built on the CPU at upload).
#pragma once

#include "vots/render/GpuLayout.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::render {

inline constexpr std::uint32_t EMPTY_CELL = 0xffffffffu; // a background cell: no Vot covers it

/// What vot_walk.frag reads besides the Vot records. Cells and bricks are stored x fastest.
struct VotWalkGrid {
    std::array<int, 3> cells{0, 0, 0};  // cells per axis: grid points - 1
    std::array<int, 3> bricks{0, 0, 0}; // bricks per axis: ceil(cells / brick side)
    int brickShift = 3;                 // brick side = 1 << brickShift cells
    std::vector<std::uint32_t> cellVot; // index into the Vot array covering the cell, or EMPTY_CELL
    std::vector<float> brickMax;        // max upperBound over the Vots touching the brick, or -inf
};

/// Builds the grid for Vots (in their GPU order) on a grid of `dims` points. Returns nullopt, with the
/// reason in *whyNot, when the walk could not see every Vot: boxes that overlap (a cell covered twice,
/// as the paper method produces) or leave the grid.
std::optional<VotWalkGrid> buildVotWalkGrid(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims,
                                            int brickShift, std::string* whyNot);

} // namespace vots::render
