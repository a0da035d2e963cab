// Rasterises disjoint Vot boxes into a cell index grid and takes per-brick maxima of their bounds.
#include "VotWalkGrid.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

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
            lo[a] = static_cast<int>(v.lo[a]);
            hi[a] = static_cast<int>(v.hi[a]);
            if (float(lo[a]) != v.lo[a] || float(hi[a]) != v.hi[a] || lo[a] < 0 || hi[a] > grid.cells[a] ||
                lo[a] >= hi[a])
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
    return grid;
}

} // namespace vots::render
