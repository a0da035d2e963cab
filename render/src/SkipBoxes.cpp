// Greedy growth of skip boxes over a per-cell bound array, split over the cores.
#include "SkipBoxes.h"

#include "ParallelChunks.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

std::vector<CellBlock> growSkipBoxes(const SkipGrowthInput& input, const std::atomic<bool>& cancel) {
    const auto& n = input.cells;
    const std::size_t votCount = input.votBoxes.size();
    // Checked often: at idle priority a growth may get little CPU, and a cancelled one should end soon.
    auto cancelled = [&] { return cancel.load(std::memory_order_relaxed); };
    const std::size_t nx = static_cast<std::size_t>(n[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(n[1]);
    // Each cell's bound (-inf for background), so that a layer is scanned row by row without looking up
    // the Vot of every cell.
    std::vector<float> cellBound(input.cellVot.size());
    for (std::size_t c = 0; c < cellBound.size(); ++c) {
        if ((c & 0xffff) == 0 && cancelled()) return {};
        const std::uint32_t id = input.cellVot[c];
        cellBound[c] = id < votCount ? input.votBounds[id] : -INFINITY;
    }
    std::vector<CellBlock> skipBoxes(votCount + input.emptyBlocks.size());
    auto grow = [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            if ((i & 63) == 0 && cancelled()) return;
            const bool isVot = i < votCount;
            const float bound = isVot ? input.votBounds[i] : -INFINITY;
            CellBlock b = isVot ? input.votBoxes[i] : input.emptyBlocks[i - votCount];
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
                    for (int y = layer.lo[1]; y < layer.hi[1]; ++y) {
                        const float* row = cellBound.data() + static_cast<std::size_t>(z) * nxy +
                                           static_cast<std::size_t>(y) * nx;
                        float rowMax = -INFINITY;
                        for (int x = layer.lo[0]; x < layer.hi[0]; ++x)
                            rowMax = std::max(rowMax, row[x]);
                        if (rowMax > bound) return false;
                    }
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
