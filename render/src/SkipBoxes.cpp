// Greedy growth of skip boxes over the walk grid's brick index, split over the cores.
#include "SkipBoxes.h"

#include "ParallelChunks.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

namespace {

// Whether every cell of the row [x0, x1) x {y} x {z} names background or a Vot whose bound is at most
// `bound`. A brick of one block is judged by that block once, so that the growth reads the index, not
// a per-cell copy of it, at about the speed of one.
bool rowWithin(const SkipGrowthInput& in, int x0, int x1, int y, int z, float bound) {
    const VotWalkGrid& g = in.grid;
    const PalettedCells& index = g.index;
    const int shift = g.brickShift, mask = (1 << shift) - 1;
    const std::size_t votCount = in.votBounds.size();
    const std::size_t brickRow =
        static_cast<std::size_t>(g.bricks[0]) *
        (static_cast<std::size_t>(y >> shift) +
         static_cast<std::size_t>(g.bricks[1]) * static_cast<std::size_t>(z >> shift));
    const std::size_t rowInBrick = static_cast<std::size_t>(((z & mask) << shift | (y & mask)) << shift);
    auto beyond = [&](std::uint32_t id) { return id < votCount && in.votBounds[id] > bound; };
    for (int x = x0; x < x1;) {
        const std::size_t brick = brickRow + static_cast<std::size_t>(x >> shift);
        const int end = std::min(x1, ((x >> shift) + 1) << shift);
        const std::uint32_t* palette = &index.palette[index.paletteStart[brick]];
        if ((index.cellTable[brick] & ((1u << CELL_TABLE_CODE_BITS) - 1)) == 0) {
            if (beyond(palette[0])) return false;
        } else {
            for (int c = x; c < end; ++c)
                if (beyond(palette[paletteIndexOf(index, brick,
                                                  rowInBrick | static_cast<std::size_t>(c & mask))]))
                    return false;
        }
        x = end;
    }
    return true;
}

} // namespace

std::vector<CellBlock> growSkipBoxes(const SkipGrowthInput& input, const std::atomic<bool>& cancel) {
    const auto& n = input.grid.cells;
    const std::size_t votCount = input.votBoxes.size();
    const std::vector<CellBlock>& emptyBlocks = input.grid.emptyBlocks;
    // Checked often: at idle priority a growth may get little CPU, and a cancelled one should end soon.
    auto cancelled = [&] { return cancel.load(std::memory_order_relaxed); };
    std::vector<CellBlock> skipBoxes(votCount + emptyBlocks.size());
    auto grow = [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            if ((i & 63) == 0 && cancelled()) return;
            const bool isVot = i < votCount;
            const float bound = isVot ? input.votBounds[i] : -INFINITY;
            CellBlock b = isVot ? input.votBoxes[i] : emptyBlocks[i - votCount];
            const CellBlock own = b;
            auto layerPasses = [&](int axis, bool up) {
                CellBlock layer = b;
                if (up) {
                    if (b.hi[axis] >= n[axis] || b.hi[axis] - own.hi[axis] >= MAX_SKIP_GROWTH) return false;
                    layer.lo[axis] = b.hi[axis];
                    layer.hi[axis] = b.hi[axis] + 1;
                } else {
                    if (b.lo[axis] <= 0 || own.lo[axis] - b.lo[axis] >= MAX_SKIP_GROWTH) return false;
                    layer.lo[axis] = b.lo[axis] - 1;
                    layer.hi[axis] = b.lo[axis];
                }
                for (int z = layer.lo[2]; z < layer.hi[2]; ++z)
                    for (int y = layer.lo[1]; y < layer.hi[1]; ++y)
                        if (!rowWithin(input, layer.lo[0], layer.hi[0], y, z, bound)) return false;
                return true;
            };
            // A direction once blocked stays blocked: its next layer would contain the blocking cell.
            bool open[6] = {true, true, true, true, true, true};
            for (bool grown = true; grown;) {
                grown = false;
                for (int d = 0; d < 6; ++d) {
                    const int axis = d % 3;
                    const bool up = d < 3;
                    if (!open[d] || !(open[d] = layerPasses(axis, up))) continue;
                    if (up)
                        ++b.hi[axis];
                    else
                        --b.lo[axis];
                    grown = true;
                }
            }
            skipBoxes[i] = b;
        }
    };
    parallelChunks(skipBoxes.size(), grow);
    if (cancelled()) return {};
    return skipBoxes;
}

} // namespace vots::render
