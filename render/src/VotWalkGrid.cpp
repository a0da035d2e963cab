// Builds the walk's brick index from disjoint Vot boxes, brick by brick: palettes, packed cell tables,
// maxima.
#include "VotWalkGrid.h"

#include "ParallelChunks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>

namespace vots::render {

namespace {

constexpr std::uint32_t OUTSIDE = EMPTY_CELL - 1;     // a cell of a partial brick beyond the grid
constexpr std::uint32_t EMPTY_LOCAL = 0x80000000u;    // | k: the brick's k-th empty block, until numbered
constexpr std::uint32_t MAX_VOTS = EMPTY_LOCAL - 1;   // Vot ids must stay below the flag
constexpr std::uint32_t MAX_BLOCKS = EMPTY_CELL - 16; // Vots + empty blocks, with room for the markers

// The Vots whose boxes touch each brick, as offsets into one list (brick b: [start[b], start[b + 1])).
struct BrickBins {
    std::vector<std::size_t> start;
    std::vector<std::uint32_t> vots;
};

BrickBins binVots(const std::vector<CellBlock>& boxes, const std::array<int, 3>& bricks, int shift) {
    const std::size_t bx = static_cast<std::size_t>(bricks[0]);
    const std::size_t bxy = bx * static_cast<std::size_t>(bricks[1]);
    BrickBins bins;
    bins.start.assign(bxy * static_cast<std::size_t>(bricks[2]) + 1, 0);
    auto forBricks = [&](const CellBlock& b, auto&& visit) {
        for (int z = b.lo[2] >> shift; z <= (b.hi[2] - 1) >> shift; ++z)
            for (int y = b.lo[1] >> shift; y <= (b.hi[1] - 1) >> shift; ++y)
                for (int x = b.lo[0] >> shift; x <= (b.hi[0] - 1) >> shift; ++x)
                    visit(static_cast<std::size_t>(z) * bxy + static_cast<std::size_t>(y) * bx +
                          static_cast<std::size_t>(x));
    };
    for (const CellBlock& b : boxes)
        forBricks(b, [&](std::size_t brick) { ++bins.start[brick + 1]; });
    for (std::size_t i = 1; i < bins.start.size(); ++i)
        bins.start[i] += bins.start[i - 1];
    bins.vots.resize(bins.start.back());
    std::vector<std::size_t> next(bins.start.begin(), bins.start.end() - 1);
    for (std::size_t i = 0; i < boxes.size(); ++i)
        forBricks(boxes[i],
                  [&](std::size_t brick) { bins.vots[next[brick]++] = static_cast<std::uint32_t>(i); });
    return bins;
}

// One brick's part of the index, with its empty blocks numbered from 0 (EMPTY_LOCAL | k in its palette).
struct BrickIndex {
    std::vector<std::uint32_t> palette;
    std::vector<std::uint32_t> table; // packed palette indices, empty for a brick of one block
    std::uint32_t code = 0;
    std::vector<CellBlock> emptyBlocks;
};

// Everything one thread reuses from brick to brick.
struct BrickScratch {
    std::vector<std::uint32_t> ids;     // per cell of the brick, x fastest
    std::vector<std::uint16_t> local;   // per cell: palette index
    std::vector<std::uint32_t> seenVot; // per Vot: the brick that last gave it a palette entry
    std::vector<std::uint16_t> votLocal;
    std::vector<std::uint16_t> emptyLocal; // per empty block of the brick: its palette index
};

// Covers the brick's background cells (EMPTY_CELL in ids, brick-local coordinates [0, extent)) with
// disjoint blocks grown from the first free cell in scan order one layer at a time along +x, +y, +z in
// turn while the new layer is all free: near-cubic blocks suit rays from any direction.
void coverEmptyCells(std::vector<std::uint32_t>& ids, int side, const std::array<int, 3>& extent,
                     const std::array<int, 3>& origin, std::vector<CellBlock>& blocks) {
    auto at = [&](int x, int y, int z) -> std::uint32_t& {
        return ids[static_cast<std::size_t>((z * side + y) * side + x)];
    };
    auto layerFree = [&](const CellBlock& b, int axis) {
        if (b.hi[axis] >= extent[axis]) return false;
        CellBlock layer = b;
        layer.lo[axis] = b.hi[axis];
        layer.hi[axis] = b.hi[axis] + 1;
        for (int z = layer.lo[2]; z < layer.hi[2]; ++z)
            for (int y = layer.lo[1]; y < layer.hi[1]; ++y)
                for (int x = layer.lo[0]; x < layer.hi[0]; ++x)
                    if (at(x, y, z) != EMPTY_CELL) return false;
        return true;
    };
    for (int z = 0; z < extent[2]; ++z)
        for (int y = 0; y < extent[1]; ++y)
            for (int x = 0; x < extent[0]; ++x) {
                if (at(x, y, z) != EMPTY_CELL) continue;
                CellBlock b{{x, y, z}, {x + 1, y + 1, z + 1}};
                for (bool grown = true; grown;) {
                    grown = false;
                    for (int axis = 0; axis < 3; ++axis)
                        if (layerFree(b, axis)) ++b.hi[axis], grown = true;
                }
                const auto id = EMPTY_LOCAL | static_cast<std::uint32_t>(blocks.size());
                for (int k = b.lo[2]; k < b.hi[2]; ++k)
                    for (int j = b.lo[1]; j < b.hi[1]; ++j)
                        std::fill(&at(b.lo[0], j, k), &at(b.lo[0], j, k) + (b.hi[0] - b.lo[0]), id);
                for (int a = 0; a < 3; ++a)
                    b.lo[a] += origin[a], b.hi[a] += origin[a];
                blocks.push_back(b);
            }
}

// The brick's cells painted with the Vots of its bin and its own empty blocks, then paletted and packed.
// Returns false, with the cell in *overlap, when two Vots share a cell.
bool indexBrick(const VotWalkGrid& grid, std::size_t brick, const std::vector<CellBlock>& boxes,
                const BrickBins& bins, BrickScratch& s, BrickIndex& out, std::array<int, 3>* overlap) {
    const int shift = grid.brickShift, side = 1 << shift;
    const std::size_t yz = brick / static_cast<std::size_t>(grid.bricks[0]);
    const std::array<int, 3> origin{static_cast<int>(brick % static_cast<std::size_t>(grid.bricks[0])) * side,
                                    static_cast<int>(yz % static_cast<std::size_t>(grid.bricks[1])) * side,
                                    static_cast<int>(yz / static_cast<std::size_t>(grid.bricks[1])) * side};
    std::array<int, 3> extent{};
    for (int a = 0; a < 3; ++a)
        extent[a] = std::min(side, grid.cells[a] - origin[a]);
    // Most bricks lie in one Vot or in background alone: their one block is known without painting a
    // cell, which keeps the build's time with the mixed bricks rather than the cells. The same palette
    // and block as painting gives (one block grown over the whole brick, no table).
    const std::size_t touching = bins.start[brick + 1] - bins.start[brick];
    if (touching == 0) {
        out.emptyBlocks.push_back(
            {origin, {origin[0] + extent[0], origin[1] + extent[1], origin[2] + extent[2]}});
        out.palette.push_back(EMPTY_LOCAL);
        return true;
    }
    if (touching == 1) {
        const std::uint32_t vot = bins.vots[bins.start[brick]];
        const CellBlock& b = boxes[vot];
        bool covers = true;
        for (int a = 0; a < 3; ++a)
            covers = covers && b.lo[a] <= origin[a] && b.hi[a] >= origin[a] + extent[a];
        if (covers) {
            out.palette.push_back(vot);
            return true;
        }
    }
    std::fill(s.ids.begin(), s.ids.end(), OUTSIDE);
    for (int z = 0; z < extent[2]; ++z)
        for (int y = 0; y < extent[1]; ++y)
            std::fill_n(&s.ids[static_cast<std::size_t>((z * side + y) * side)], extent[0], EMPTY_CELL);
    for (std::size_t k = bins.start[brick]; k < bins.start[brick + 1]; ++k) {
        const std::uint32_t vot = bins.vots[k];
        const CellBlock& b = boxes[vot];
        std::array<int, 3> lo{}, hi{};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(b.lo[a] - origin[a], 0);
            hi[a] = std::min(b.hi[a] - origin[a], extent[a]);
        }
        for (int z = lo[2]; z < hi[2]; ++z)
            for (int y = lo[1]; y < hi[1]; ++y)
                for (int x = lo[0]; x < hi[0]; ++x) {
                    std::uint32_t& id = s.ids[static_cast<std::size_t>((z * side + y) * side + x)];
                    if (id != EMPTY_CELL) {
                        *overlap = {origin[0] + x, origin[1] + y, origin[2] + z};
                        return false;
                    }
                    id = vot;
                }
    }
    coverEmptyCells(s.ids, side, extent, origin, out.emptyBlocks);

    // Palette in order of first appearance (x fastest), as the shader's cells name them.
    std::fill(s.emptyLocal.begin(),
              s.emptyLocal.begin() + static_cast<std::ptrdiff_t>(out.emptyBlocks.size()),
              std::uint16_t{0xffff});
    for (std::size_t c = 0; c < s.ids.size(); ++c) {
        const std::uint32_t id = s.ids[c];
        std::uint16_t& local = s.local[c];
        if (id == OUTSIDE) {
            local = 0;
        } else if (id & EMPTY_LOCAL) {
            std::uint16_t& l = s.emptyLocal[id & ~EMPTY_LOCAL];
            if (l == 0xffff) l = static_cast<std::uint16_t>(out.palette.size()), out.palette.push_back(id);
            local = l;
        } else {
            if (s.seenVot[id] != brick) {
                s.seenVot[id] = static_cast<std::uint32_t>(brick);
                s.votLocal[id] = static_cast<std::uint16_t>(out.palette.size());
                out.palette.push_back(id);
            }
            local = s.votLocal[id];
        }
    }
    if (out.palette.size() <= 1) return true; // one block: the brick needs no table
    out.code = 1;                             // bits = 2^(code - 1)
    while ((std::size_t{1} << (std::size_t{1} << (out.code - 1))) < out.palette.size())
        ++out.code;
    const std::size_t bits = std::size_t{1} << (out.code - 1);
    out.table.assign((s.ids.size() * bits / 32 + 3) / 4 * 4, 0u);
    for (std::size_t i = 0; i < s.ids.size(); ++i)
        out.table[i * bits / 32] |= std::uint32_t{s.local[i]} << (i * bits % 32);
    return true;
}

} // namespace

std::uint32_t blockAt(const VotWalkGrid& grid, const std::array<int, 3>& cell) {
    const int shift = grid.brickShift;
    const std::size_t brick =
        static_cast<std::size_t>(cell[0] >> shift) +
        static_cast<std::size_t>(grid.bricks[0]) *
            (static_cast<std::size_t>(cell[1] >> shift) +
             static_cast<std::size_t>(grid.bricks[1]) * static_cast<std::size_t>(cell[2] >> shift));
    const int mask = (1 << shift) - 1;
    const std::size_t inBrick = static_cast<std::size_t>(
        (((cell[2] & mask) << shift | (cell[1] & mask)) << shift) | (cell[0] & mask));
    return grid.index.palette[grid.index.paletteStart[brick] + paletteIndexOf(grid.index, brick, inBrick)];
}

std::optional<VotWalkGrid> buildVotWalkGrid(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims,
                                            int brickShift, std::string* whyNot) {
    auto fail = [&](std::string reason) -> std::optional<VotWalkGrid> {
        if (whyNot) *whyNot = std::move(reason);
        return std::nullopt;
    };
    VotWalkGrid grid;
    grid.brickShift = brickShift;
    std::size_t brickCount = 1;
    for (int a = 0; a < 3; ++a) {
        if (dims[a] < 2) return fail("grid has fewer than 2 points along an axis");
        grid.cells[a] = dims[a] - 1;
        grid.bricks[a] = ((grid.cells[a] - 1) >> brickShift) + 1;
        brickCount *= static_cast<std::size_t>(grid.bricks[a]);
    }
    if (vots.size() >= MAX_VOTS) return fail("too many Vots for 31-bit cell indices");
    std::vector<CellBlock> boxes(vots.size());
    for (std::size_t i = 0; i < vots.size(); ++i) {
        const GpuVot& v = vots[i];
        for (int a = 0; a < 3; ++a) {
            // In range first (NaN fails too), so that the int conversions are defined.
            const bool inside = v.lo[a] >= 0.f && v.hi[a] <= float(grid.cells[a]) && v.lo[a] < v.hi[a];
            boxes[i].lo[a] = inside ? static_cast<int>(v.lo[a]) : 0;
            boxes[i].hi[a] = inside ? static_cast<int>(v.hi[a]) : 0;
            if (!inside || float(boxes[i].lo[a]) != v.lo[a] || float(boxes[i].hi[a]) != v.hi[a])
                return fail("Vot " + std::to_string(i) +
                            " has a box that is not a cell block inside the grid");
        }
    }
    const BrickBins bins = binVots(boxes, grid.bricks, brickShift);
    grid.brickMax.assign(brickCount, -INFINITY);
    for (std::size_t brick = 0; brick < brickCount; ++brick)
        for (std::size_t k = bins.start[brick]; k < bins.start[brick + 1]; ++k)
            grid.brickMax[brick] = std::max(grid.brickMax[brick], vots[bins.vots[k]].upperBound);

    const std::size_t brickCells = std::size_t{1} << (3 * brickShift);
    std::vector<BrickIndex> bricks(brickCount);
    std::atomic<bool> overlapped{false};
    std::array<int, 3> overlapCell{-1, -1, -1};
    std::mutex overlapLock;
    // Split by cells so that every core gets a share of the bricks (parallelChunks splits only large counts).
    parallelChunks(brickCount * brickCells, [&](std::size_t firstCell, std::size_t lastCell) {
        BrickScratch s;
        s.ids.resize(brickCells);
        s.local.resize(brickCells);
        s.seenVot.assign(vots.size(), UINT32_MAX);
        s.votLocal.resize(vots.size());
        s.emptyLocal.resize(brickCells);
        for (std::size_t brick = firstCell / brickCells; brick < lastCell / brickCells; ++brick) {
            if (overlapped.load(std::memory_order_relaxed)) return;
            std::array<int, 3> cell{};
            if (!indexBrick(grid, brick, boxes, bins, s, bricks[brick], &cell)) {
                const std::lock_guard<std::mutex> lock(overlapLock);
                overlapCell = cell;
                overlapped = true;
            }
        }
    });
    if (overlapped)
        return fail("Vot boxes overlap (cell " + std::to_string(overlapCell[0]) + "," +
                    std::to_string(overlapCell[1]) + "," + std::to_string(overlapCell[2]) + ")");

    // Number the empty blocks brick after brick and concatenate the bricks' palettes and tables.
    PalettedCells& index = grid.index;
    index.paletteStart.resize(brickCount);
    index.cellTable.resize(brickCount);
    std::size_t paletteSize = 0, words = 0, empties = 0;
    for (const BrickIndex& b : bricks)
        paletteSize += b.palette.size(), words += b.table.size(), empties += b.emptyBlocks.size();
    if (vots.size() + empties >= MAX_BLOCKS) return fail("too many blocks for 32-bit indices");
    index.palette.reserve(std::max<std::size_t>(paletteSize, 1));
    index.cellWords.reserve(std::max<std::size_t>(words, 4));
    grid.emptyBlocks.reserve(empties);
    for (std::size_t brick = 0; brick < brickCount; ++brick) {
        BrickIndex& b = bricks[brick];
        const auto firstEmpty = static_cast<std::uint32_t>(vots.size() + grid.emptyBlocks.size());
        index.paletteStart[brick] = static_cast<std::uint32_t>(index.palette.size());
        for (const std::uint32_t id : b.palette)
            index.palette.push_back(id & EMPTY_LOCAL ? firstEmpty + (id & ~EMPTY_LOCAL) : id);
        // Offsets past MAX_CELL_WORDS wrap; the caller checks cellWords.size() against it.
        index.cellTable[brick] =
            static_cast<std::uint32_t>(index.cellWords.size() << CELL_TABLE_CODE_BITS) | b.code;
        index.cellWords.insert(index.cellWords.end(), b.table.begin(), b.table.end());
        grid.emptyBlocks.insert(grid.emptyBlocks.end(), b.emptyBlocks.begin(), b.emptyBlocks.end());
        b = BrickIndex{};
    }
    if (index.palette.empty()) index.palette.push_back(0); // a buffer texture needs a texel
    if (index.cellWords.empty()) index.cellWords.assign(4, 0u);
    return grid;
}

} // namespace vots::render
