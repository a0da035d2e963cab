// Cell -> Vot index grid and per-brick bound maxima for the Walk MIP strategy (built on the CPU at upload).
#pragma once

#include "vots/render/GpuLayout.h"

#include <array>
#include <cstddef>
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

/// The cell grid as vot_walk.glsl reads it, in a size that follows the Vots rather than the cells: each
/// brick has a palette of the block ids its cells name; a brick whose cells all name one block (inside
/// one Vot, or background) stores nothing more, and a mixed brick stores each cell's index into its
/// palette in as few bits as the palette needs (1, 2, 4, 8 or 16). A mixed brick's cells are packed x
/// fastest, cell i at bit i * bits of its table, so that a ray stays in few cache lines; the walk waits
/// on these reads more than on anything else.
struct PalettedCells {
    std::vector<std::uint32_t> cellWords;    // the mixed bricks' tables, each padded to a multiple of 4
                                             // words (one RGBA32UI texel)
    std::vector<std::uint32_t> cellTable;    // per brick: word offset << 3 | width code (below)
    std::vector<std::uint32_t> palette;      // block ids (VotWalkGrid), brick after brick
    std::vector<std::uint32_t> paletteStart; // per brick: the index of its first palette entry
};

/// A brick's cellTable word: its table's first word in cellWords and a width code, 0 for a brick with
/// one palette entry (no table), k for 2^(k-1) bits per cell.
inline constexpr int CELL_TABLE_CODE_BITS = 3;
/// Offsets stay below 2^29 words (2 GiB) so that offset and code fit 32 bits.
inline constexpr std::size_t MAX_CELL_WORDS = std::size_t{1} << (32 - CELL_TABLE_CODE_BITS);

/// The palette index of cell `inBrick` (x fastest inside the brick) of brick `brick`, as the shader
/// decodes it.
inline std::uint32_t paletteIndexOf(const PalettedCells& cells, std::size_t brick, std::size_t inBrick) {
    const std::uint32_t table = cells.cellTable[brick];
    const std::uint32_t code = table & ((1u << CELL_TABLE_CODE_BITS) - 1);
    if (code == 0) return 0;
    const std::size_t bits = std::size_t{1} << (code - 1);
    const std::size_t bit = inBrick * bits;
    const std::uint32_t word = cells.cellWords[(table >> CELL_TABLE_CODE_BITS) + bit / 32];
    return (word >> (bit % 32)) & ((1u << bits) - 1);
}

/// What the walk shader (vot_walk.glsl) reads besides the Vot records. Bricks are stored x fastest. Block
/// ids: below the Vot count, the Vot's index; from it up, the Vot count + an index into emptyBlocks.
struct VotWalkGrid {
    std::array<int, 3> cells{0, 0, 0};  // cells per axis: grid points - 1
    std::array<int, 3> bricks{0, 0, 0}; // bricks per axis: ceil(cells / brick side)
    int brickShift = 3;                 // brick side = 1 << brickShift cells
    std::vector<float> brickMax;        // max upperBound over the Vots touching the brick, or -inf
    std::vector<CellBlock> emptyBlocks; // disjoint blocks, each inside one brick, covering every
                                        // background cell, so the walk crosses empty space in few steps
    PalettedCells index;                // each cell's block id, per brick
};

/// The block id of a cell inside the grid.
std::uint32_t blockAt(const VotWalkGrid& grid, const std::array<int, 3>& cell);

/// Builds the grid for Vots (in their GPU order) on a grid of `dims` points. Returns nullopt, with the
/// reason in *whyNot, when the walk could not see every Vot: boxes that overlap (a cell covered twice,
/// as the paper method produces) or leave the grid. Works brick by brick, so that its memory follows
/// the Vots and the mixed bricks, never the cell count; background cells are covered greedily with
/// near-cubic empty blocks inside each brick (the walk steps over all-background bricks whole).
std::optional<VotWalkGrid> buildVotWalkGrid(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims,
                                            int brickShift, std::string* whyNot);

} // namespace vots::render
