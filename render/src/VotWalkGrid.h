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

/// A block of cells [lo, hi) (cell coordinates; hi exclusive).
struct CellBlock {
    std::array<int, 3> lo{0, 0, 0};
    std::array<int, 3> hi{0, 0, 0};
};

/// A Vot record's box as a cell block (the corners of a walkable Vot are whole cells).
inline CellBlock cellBlockOf(const GpuVot& v) {
    return {{int(v.lo[0]), int(v.lo[1]), int(v.lo[2])}, {int(v.hi[0]), int(v.hi[1]), int(v.hi[2])}};
}

/// Box corners in 16 bits each into three words, as unpackBox in vot_walk.glsl reads them (the box table
/// and the walk records): lo.x | lo.y << 16, lo.z | hi.x << 16, hi.y | hi.z << 16.
inline void packBoxCorners(std::uint32_t* words, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
    const auto u16 = [](int v) { return static_cast<std::uint32_t>(v) & 0xffffu; };
    words[0] = u16(lo[0]) | u16(lo[1]) << 16;
    words[1] = u16(lo[2]) | u16(hi[0]) << 16;
    words[2] = u16(hi[1]) | u16(hi[2]) << 16;
}

/// What the walk shader (vot_walk.glsl) reads besides the Vot records. Cells and bricks are stored x fastest.
struct VotWalkGrid {
    std::array<int, 3> cells{0, 0, 0};  // cells per axis: grid points - 1
    std::array<int, 3> bricks{0, 0, 0}; // bricks per axis: ceil(cells / brick side)
    int brickShift = 3;                 // brick side = 1 << brickShift cells
    std::vector<std::uint32_t> cellVot; // < Vot count: the Vot covering the cell; else Vot count + index
                                        // into emptyBlocks
    std::vector<float> brickMax;        // max upperBound over the Vots touching the brick, or -inf
    std::vector<CellBlock> emptyBlocks; // disjoint blocks covering every background cell, so the walk
                                        // crosses empty space in a few steps
};

/// The cell grid as vot_walk.glsl reads it, in half the bytes of cellVot: each brick has a palette of
/// the block ids its cells name, and each cell holds its index into that palette. Cells are stored
/// brick by brick (bricks x fastest, cells x fastest inside a brick, padded to whole bricks), so a ray
/// stays in few cache lines; the walk waits on these reads more than on anything else.
struct PalettedCells {
    std::vector<std::uint16_t> local;        // per cell: index into its brick's palette (a brick has 4096
                                             // cells at most, so 16 bits always do)
    std::vector<std::uint32_t> palette;      // block ids (as cellVot), brick after brick
    std::vector<std::uint32_t> paletteStart; // per brick: the index of its first palette entry
};
PalettedCells palettedCells(const VotWalkGrid& grid);

/// Builds the grid for Vots (in their GPU order) on a grid of `dims` points. Returns nullopt, with the
/// reason in *whyNot, when the walk could not see every Vot: boxes that overlap (a cell covered twice,
/// as the paper method produces) or leave the grid. Background cells are covered greedily with
/// near-cubic empty blocks.
std::optional<VotWalkGrid> buildVotWalkGrid(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims,
                                            int brickShift, std::string* whyNot);

} // namespace vots::render
