// Rasterises disjoint Vot boxes into a cell index grid and takes per-brick maxima of their bounds.
#include "VotWalkGrid.h"

#include "ParallelChunks.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

namespace {

// Covers every EMPTY_CELL of grid.cellVot with disjoint blocks, grown from the first free cell in scan
// order one layer at a time along +x, +y, +z in turn while the new layer is all free (near-cubic
// blocks suit rays from any direction). Each covered cell gets base + block index.
void coverEmptyCells(VotWalkGrid& grid, std::uint32_t base) {
    const auto& n = grid.cells;
    const std::size_t nx = static_cast<std::size_t>(n[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(n[1]);
    auto at = [&](int x, int y, int z) -> std::uint32_t& {
        return grid.cellVot[static_cast<std::size_t>(z) * nxy + static_cast<std::size_t>(y) * nx +
                            static_cast<std::size_t>(x)];
    };
    auto layerFree = [&](const CellBlock& b, int axis) {
        CellBlock layer = b;
        layer.lo[axis] = b.hi[axis];
        layer.hi[axis] = b.hi[axis] + 1;
        if (layer.hi[axis] > n[axis]) return false;
        for (int z = layer.lo[2]; z < layer.hi[2]; ++z)
            for (int y = layer.lo[1]; y < layer.hi[1]; ++y)
                for (int x = layer.lo[0]; x < layer.hi[0]; ++x)
                    if (at(x, y, z) != EMPTY_CELL) return false;
        return true;
    };
    for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y)
            for (int x = 0; x < n[0]; ++x) {
                if (at(x, y, z) != EMPTY_CELL) continue;
                CellBlock b{{x, y, z}, {x + 1, y + 1, z + 1}};
                for (bool grown = true; grown;) {
                    grown = false;
                    for (int axis = 0; axis < 3; ++axis)
                        if (layerFree(b, axis)) ++b.hi[axis], grown = true;
                }
                const auto index = base + static_cast<std::uint32_t>(grid.emptyBlocks.size());
                for (int k = b.lo[2]; k < b.hi[2]; ++k)
                    for (int j = b.lo[1]; j < b.hi[1]; ++j)
                        for (int i = b.lo[0]; i < b.hi[0]; ++i)
                            at(i, j, k) = index;
                grid.emptyBlocks.push_back(b);
            }
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
    if (vots.size() >= EMPTY_CELL) return fail("too many Vots for 32-bit cell indices");
    grid.cellVot.assign(cellCount, EMPTY_CELL);
    grid.brickMax.assign(brickCount, -INFINITY);
    const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(grid.cells[1]);
    const std::size_t bx = static_cast<std::size_t>(grid.bricks[0]);
    const std::size_t bxy = bx * static_cast<std::size_t>(grid.bricks[1]);
    for (std::size_t i = 0; i < vots.size(); ++i) {
        const GpuVot& v = vots[i];
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            // In range first (NaN fails too), so that the int conversions are defined.
            const bool inside = v.lo[a] >= 0.f && v.hi[a] <= float(grid.cells[a]) && v.lo[a] < v.hi[a];
            lo[a] = inside ? static_cast<int>(v.lo[a]) : 0;
            hi[a] = inside ? static_cast<int>(v.hi[a]) : 0;
            if (!inside || float(lo[a]) != v.lo[a] || float(hi[a]) != v.hi[a])
                return fail("Vot " + std::to_string(i) +
                            " has a box that is not a cell block inside the grid");
        }
        const auto index = static_cast<std::uint32_t>(i);
        for (int z = lo[2]; z < hi[2]; ++z)
            for (int y = lo[1]; y < hi[1]; ++y) {
                std::uint32_t* row = grid.cellVot.data() + static_cast<std::size_t>(z) * nxy +
                                     static_cast<std::size_t>(y) * nx;
                for (int x = lo[0]; x < hi[0]; ++x) {
                    if (row[x] != EMPTY_CELL)
                        return fail("Vot boxes overlap (cell " + std::to_string(x) + "," + std::to_string(y) +
                                    "," + std::to_string(z) + ")");
                    row[x] = index;
                }
            }
        for (int z = lo[2] >> brickShift; z <= (hi[2] - 1) >> brickShift; ++z)
            for (int y = lo[1] >> brickShift; y <= (hi[1] - 1) >> brickShift; ++y)
                for (int x = lo[0] >> brickShift; x <= (hi[0] - 1) >> brickShift; ++x) {
                    float& m = grid.brickMax[static_cast<std::size_t>(z) * bxy +
                                             static_cast<std::size_t>(y) * bx + static_cast<std::size_t>(x)];
                    m = std::max(m, v.upperBound);
                }
    }
    coverEmptyCells(grid, static_cast<std::uint32_t>(vots.size()));
    if (vots.size() + grid.emptyBlocks.size() >= EMPTY_CELL)
        return fail("too many blocks for 32-bit indices");
    return grid;
}

} // namespace vots::render

namespace vots::render {

PalettedCells palettedCells(const VotWalkGrid& grid) {
    const int side = 1 << grid.brickShift;
    const std::size_t brickCells = std::size_t{1} << (3 * grid.brickShift);
    const std::size_t brickCount = grid.brickMax.size();
    PalettedCells out;
    out.local.assign(brickCount * brickCells, 0);
    std::uint32_t ids = 1;
    for (const std::uint32_t id : grid.cellVot)
        ids = std::max(ids, id + 1);
    const std::size_t nx = static_cast<std::size_t>(grid.cells[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(grid.cells[1]);
    std::vector<std::vector<std::uint32_t>> palettes(brickCount);
    // Split by cells so that every core gets a share of the bricks (parallelChunks splits only large counts).
    parallelChunks(out.local.size(), [&](std::size_t firstCell, std::size_t lastCell) {
        // Which brick last gave each id a palette entry, and that entry's index in the brick's palette.
        std::vector<std::uint32_t> seenInBrick(ids, UINT32_MAX);
        std::vector<std::uint16_t> localOf(ids, 0);
        for (std::size_t brick = firstCell / brickCells; brick < lastCell / brickCells; ++brick) {
            std::vector<std::uint32_t>& palette = palettes[brick];
            std::uint16_t* local = &out.local[brick * brickCells];
            const int x0 = static_cast<int>(brick % static_cast<std::size_t>(grid.bricks[0])) * side;
            const std::size_t yz = brick / static_cast<std::size_t>(grid.bricks[0]);
            const int y0 = static_cast<int>(yz % static_cast<std::size_t>(grid.bricks[1])) * side;
            const int z0 = static_cast<int>(yz / static_cast<std::size_t>(grid.bricks[1])) * side;
            for (int z = z0; z < std::min(z0 + side, grid.cells[2]); ++z)
                for (int y = y0; y < std::min(y0 + side, grid.cells[1]); ++y) {
                    const std::size_t row =
                        static_cast<std::size_t>(z) * nxy + static_cast<std::size_t>(y) * nx;
                    std::uint16_t* localRow =
                        local + (static_cast<std::size_t>(z - z0) * static_cast<std::size_t>(side) +
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
        }
    });
    out.paletteStart.resize(brickCount);
    for (std::size_t brick = 0; brick < brickCount; ++brick) {
        out.paletteStart[brick] = static_cast<std::uint32_t>(out.palette.size());
        out.palette.insert(out.palette.end(), palettes[brick].begin(), palettes[brick].end());
    }
    if (out.palette.empty()) out.palette.push_back(0); // a buffer texture needs a texel
    return out;
}

} // namespace vots::render
