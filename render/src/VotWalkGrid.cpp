// Rasterises disjoint Vot boxes into a cell index grid and takes per-brick maxima of their bounds.
#include "VotWalkGrid.h"

#include "ParallelChunks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <thread>

namespace vots::render {

namespace {

constexpr std::uint32_t COVERED = EMPTY_CELL - 1; // a background cell some empty block has taken

// Covers every EMPTY_CELL of grid.cellVot with disjoint blocks, grown from the first free cell in scan
// order one layer at a time along +x, +y, +z in turn while the new layer is all free (near-cubic
// blocks suit rays from any direction). Each covered cell gets base + block index. The z range is cut
// into slabs covered in parallel (blocks stop at slab faces; the skip-box growth after the first frame
// joins them again); blocks are numbered slab by slab, so the result depends only on the slab count.
void coverEmptyCells(VotWalkGrid& grid, std::uint32_t base) {
    const auto& n = grid.cells;
    const std::size_t nx = static_cast<std::size_t>(n[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(n[1]);
    auto at = [&](int x, int y, int z) -> std::uint32_t& {
        return grid.cellVot[static_cast<std::size_t>(z) * nxy + static_cast<std::size_t>(y) * nx +
                            static_cast<std::size_t>(x)];
    };
    auto fill = [&](const CellBlock& b, std::uint32_t value) {
        for (int k = b.lo[2]; k < b.hi[2]; ++k)
            for (int j = b.lo[1]; j < b.hi[1]; ++j)
                std::fill(&at(b.lo[0], j, k), &at(b.lo[0], j, k) + (b.hi[0] - b.lo[0]), value);
    };
    constexpr int MIN_SLAB = 32; // cells: thinner slabs would cut too many blocks
    const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const int slabs = std::clamp(n[2] / MIN_SLAB, 1, std::min(cores, 4));
    std::vector<std::vector<CellBlock>> slabBlocks(static_cast<std::size_t>(slabs));
    parallelTasks(slabBlocks.size(), [&](std::size_t slab) {
        const int z0 = n[2] * static_cast<int>(slab) / slabs, z1 = n[2] * static_cast<int>(slab + 1) / slabs;
        std::vector<CellBlock>& blocks = slabBlocks[slab];
        auto layerFree = [&](const CellBlock& b, int axis) {
            CellBlock layer = b;
            layer.lo[axis] = b.hi[axis];
            layer.hi[axis] = b.hi[axis] + 1;
            if (layer.hi[axis] > (axis == 2 ? z1 : n[axis])) return false;
            for (int z = layer.lo[2]; z < layer.hi[2]; ++z)
                for (int y = layer.lo[1]; y < layer.hi[1]; ++y)
                    for (int x = layer.lo[0]; x < layer.hi[0]; ++x)
                        if (at(x, y, z) != EMPTY_CELL) return false;
            return true;
        };
        for (int z = z0; z < z1; ++z)
            for (int y = 0; y < n[1]; ++y)
                for (int x = 0; x < n[0]; ++x) {
                    if (at(x, y, z) != EMPTY_CELL) continue;
                    CellBlock b{{x, y, z}, {x + 1, y + 1, z + 1}};
                    for (bool grown = true; grown;) {
                        grown = false;
                        for (int axis = 0; axis < 3; ++axis)
                            if (layerFree(b, axis)) ++b.hi[axis], grown = true;
                    }
                    fill(b, COVERED);
                    blocks.push_back(b);
                }
    });
    for (const std::vector<CellBlock>& blocks : slabBlocks)
        grid.emptyBlocks.insert(grid.emptyBlocks.end(), blocks.begin(), blocks.end());
    parallelChunks(grid.emptyBlocks.size(), [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i)
            fill(grid.emptyBlocks[i], base + static_cast<std::uint32_t>(i));
    });
}

// Writes each Vot's index into its cells and its bound into the bricks it touches, Vots split among
// threads. Boxes of a walkable space are disjoint, so no cell is written twice; whether they were is
// told afterwards by counting (overlaps leave fewer covered cells than the boxes hold).
bool rasterizeVots(VotWalkGrid& grid, const std::vector<GpuVot>& vots, const std::vector<CellBlock>& boxes) {
    const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(grid.cells[1]);
    const std::size_t bx = static_cast<std::size_t>(grid.bricks[0]);
    const std::size_t bxy = bx * static_cast<std::size_t>(grid.bricks[1]);
    const int shift = grid.brickShift;
    std::mutex merge;
    std::size_t boxCells = 0;
    parallelChunks(vots.size(), [&](std::size_t first, std::size_t last) {
        std::vector<float> brickMax(grid.brickMax.size(), -INFINITY);
        std::size_t cells = 0;
        for (std::size_t i = first; i < last; ++i) {
            const CellBlock& b = boxes[i];
            const auto index = static_cast<std::uint32_t>(i);
            for (int z = b.lo[2]; z < b.hi[2]; ++z)
                for (int y = b.lo[1]; y < b.hi[1]; ++y) {
                    std::uint32_t* row = grid.cellVot.data() + static_cast<std::size_t>(z) * nxy +
                                         static_cast<std::size_t>(y) * nx;
                    for (int x = b.lo[0]; x < b.hi[0]; ++x) // atomic only so that overlaps are defined
                        std::atomic_ref<std::uint32_t>(row[x]).store(index, std::memory_order_relaxed);
                }
            cells += static_cast<std::size_t>(b.hi[0] - b.lo[0]) *
                     static_cast<std::size_t>(b.hi[1] - b.lo[1]) *
                     static_cast<std::size_t>(b.hi[2] - b.lo[2]);
            for (int z = b.lo[2] >> shift; z <= (b.hi[2] - 1) >> shift; ++z)
                for (int y = b.lo[1] >> shift; y <= (b.hi[1] - 1) >> shift; ++y)
                    for (int x = b.lo[0] >> shift; x <= (b.hi[0] - 1) >> shift; ++x) {
                        float& m = brickMax[static_cast<std::size_t>(z) * bxy +
                                            static_cast<std::size_t>(y) * bx + static_cast<std::size_t>(x)];
                        m = std::max(m, vots[i].upperBound);
                    }
        }
        const std::lock_guard<std::mutex> lock(merge);
        boxCells += cells;
        for (std::size_t i = 0; i < brickMax.size(); ++i)
            grid.brickMax[i] = std::max(grid.brickMax[i], brickMax[i]);
    });
    const auto covered = static_cast<std::size_t>(
        grid.cellVot.size() -
        static_cast<std::size_t>(std::count(grid.cellVot.begin(), grid.cellVot.end(), EMPTY_CELL)));
    return covered == boxCells;
}

// The first cell that two of the boxes share, for the error message.
std::array<int, 3> firstOverlap(const std::array<int, 3>& cells, const std::vector<CellBlock>& boxes) {
    std::vector<bool> taken(static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
                            static_cast<std::size_t>(cells[2]));
    for (const CellBlock& b : boxes)
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x) {
                    const std::size_t i = (static_cast<std::size_t>(z) * static_cast<std::size_t>(cells[1]) +
                                           static_cast<std::size_t>(y)) *
                                              static_cast<std::size_t>(cells[0]) +
                                          static_cast<std::size_t>(x);
                    if (taken[i]) return {x, y, z};
                    taken[i] = true;
                }
    return {-1, -1, -1};
}

} // namespace

std::optional<VotWalkGrid> buildVotWalkGrid(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims,
                                            int brickShift, std::string* whyNot) {
    auto fail = [&](std::string reason) -> std::optional<VotWalkGrid> {
        if (whyNot) *whyNot = std::move(reason);
        return std::nullopt;
    };
    VotWalkGrid grid;
    grid.brickShift = brickShift;
    std::size_t cellCount = 1, brickCount = 1;
    for (int a = 0; a < 3; ++a) {
        if (dims[a] < 2) return fail("grid has fewer than 2 points along an axis");
        grid.cells[a] = dims[a] - 1;
        grid.bricks[a] = ((grid.cells[a] - 1) >> brickShift) + 1;
        cellCount *= static_cast<std::size_t>(grid.cells[a]);
        brickCount *= static_cast<std::size_t>(grid.bricks[a]);
    }
    if (vots.size() >= COVERED) return fail("too many Vots for 32-bit cell indices");
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
    grid.cellVot.assign(cellCount, EMPTY_CELL);
    grid.brickMax.assign(brickCount, -INFINITY);
    if (!rasterizeVots(grid, vots, boxes)) {
        const std::array<int, 3> c = firstOverlap(grid.cells, boxes);
        return fail("Vot boxes overlap (cell " + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," +
                    std::to_string(c[2]) + ")");
    }
    coverEmptyCells(grid, static_cast<std::uint32_t>(vots.size()));
    if (vots.size() + grid.emptyBlocks.size() >= COVERED) return fail("too many blocks for 32-bit indices");
    return grid;
}

PalettedCells palettedCells(const VotWalkGrid& grid) {
    const int side = 1 << grid.brickShift;
    const std::size_t brickCells = std::size_t{1} << (3 * grid.brickShift);
    const std::size_t brickCount = grid.brickMax.size();
    std::uint32_t ids = 1;
    for (const std::uint32_t id : grid.cellVot)
        ids = std::max(ids, id + 1);
    const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(grid.cells[1]);
    std::vector<std::vector<std::uint32_t>> palettes(brickCount), tables(brickCount);
    std::vector<std::uint32_t> codes(brickCount, 0);
    // Split by cells so that every core gets a share of the bricks (parallelChunks splits only large counts).
    parallelChunks(brickCount * brickCells, [&](std::size_t firstCell, std::size_t lastCell) {
        // Which brick last gave each id a palette entry, and that entry's index in the brick's palette.
        std::vector<std::uint32_t> seenInBrick(ids, UINT32_MAX);
        std::vector<std::uint16_t> localOf(ids, 0);
        std::vector<std::uint16_t> local(brickCells);
        for (std::size_t brick = firstCell / brickCells; brick < lastCell / brickCells; ++brick) {
            std::vector<std::uint32_t>& palette = palettes[brick];
            std::fill(local.begin(), local.end(), std::uint16_t{0});
            const int x0 = static_cast<int>(brick % static_cast<std::size_t>(grid.bricks[0])) * side;
            const std::size_t yz = brick / static_cast<std::size_t>(grid.bricks[0]);
            const int y0 = static_cast<int>(yz % static_cast<std::size_t>(grid.bricks[1])) * side;
            const int z0 = static_cast<int>(yz / static_cast<std::size_t>(grid.bricks[1])) * side;
            for (int z = z0; z < std::min(z0 + side, grid.cells[2]); ++z)
                for (int y = y0; y < std::min(y0 + side, grid.cells[1]); ++y) {
                    const std::size_t row =
                        static_cast<std::size_t>(z) * nxy + static_cast<std::size_t>(y) * nx;
                    std::uint16_t* localRow =
                        local.data() + (static_cast<std::size_t>(z - z0) * static_cast<std::size_t>(side) +
                                        static_cast<std::size_t>(y - y0)) *
                                           static_cast<std::size_t>(side);
                    for (int x = x0; x < std::min(x0 + side, grid.cells[0]); ++x) {
                        const std::uint32_t id = grid.cellVot[row + static_cast<std::size_t>(x)];
                        if (seenInBrick[id] != brick) {
                            seenInBrick[id] = static_cast<std::uint32_t>(brick);
                            localOf[id] = static_cast<std::uint16_t>(palette.size());
                            palette.push_back(id);
                        }
                        localRow[x - x0] = localOf[id];
                    }
                }
            if (palette.size() <= 1) continue; // one block: the brick needs no table
            std::uint32_t code = 1;            // bits = 2^(code - 1)
            while ((std::size_t{1} << (std::size_t{1} << (code - 1))) < palette.size())
                ++code;
            codes[brick] = code;
            const std::size_t bits = std::size_t{1} << (code - 1);
            std::vector<std::uint32_t>& table = tables[brick];
            table.assign((brickCells * bits / 32 + 3) / 4 * 4, 0u);
            for (std::size_t i = 0; i < brickCells; ++i)
                table[i * bits / 32] |= std::uint32_t{local[i]} << (i * bits % 32);
        }
    });
    PalettedCells out;
    out.paletteStart.resize(brickCount);
    out.cellTable.resize(brickCount);
    std::size_t words = 0;
    for (std::size_t brick = 0; brick < brickCount; ++brick)
        words += tables[brick].size();
    out.cellWords.reserve(std::max<std::size_t>(words, 4));
    for (std::size_t brick = 0; brick < brickCount; ++brick) {
        out.paletteStart[brick] = static_cast<std::uint32_t>(out.palette.size());
        out.palette.insert(out.palette.end(), palettes[brick].begin(), palettes[brick].end());
        // Offsets past MAX_CELL_WORDS wrap; the caller checks cellWords.size() against it.
        out.cellTable[brick] =
            static_cast<std::uint32_t>(out.cellWords.size() << CELL_TABLE_CODE_BITS) | codes[brick];
        out.cellWords.insert(out.cellWords.end(), tables[brick].begin(), tables[brick].end());
        std::vector<std::uint32_t>().swap(tables[brick]);
    }
    if (out.palette.empty()) out.palette.push_back(0); // a buffer texture needs a texel
    if (out.cellWords.empty()) out.cellWords.assign(4, 0u);
    return out;
}

} // namespace vots::render
