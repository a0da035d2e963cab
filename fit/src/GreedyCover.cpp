// Lazy-greedy set cover over cells (docs/DESIGN.md §4, paper method step 3): weights rechecked when popped.
#include "PaperGrowth.h"

#include <queue>

namespace vots::fit {

std::vector<FittedBox> greedyCover(std::vector<FittedBox> candidates, const CellMask& mask,
                                   const FitControl& control) {
    const auto cells = mask.cellDims();
    auto cellIndex = [&](int i, int j, int k) {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(cells[0]) *
                   (static_cast<std::size_t>(j) + static_cast<std::size_t>(cells[1]) * k);
    };
    // Background cells need no cover: start them as covered.
    std::vector<std::uint8_t> covered(static_cast<std::size_t>(mask.totalCells()), 0);
    for (int k = 0; k < cells[2]; ++k)
        for (int j = 0; j < cells[1]; ++j)
            for (int i = 0; i < cells[0]; ++i)
                covered[cellIndex(i, j, k)] = mask.isBackground(i, j, k) ? 1 : 0;

    auto countUncovered = [&](const Box& b) {
        std::int64_t n = 0;
        for (int k = b.lo[2]; k < b.hi[2]; ++k)
            for (int j = b.lo[1]; j < b.hi[1]; ++j)
                for (int i = b.lo[0]; i < b.hi[0]; ++i)
                    n += covered[cellIndex(i, j, k)] == 0;
        return n;
    };
    using Entry = std::pair<std::int64_t, std::size_t>; // (weight, candidate)
    std::priority_queue<Entry> queue;
    for (std::size_t c = 0; c < candidates.size(); ++c)
        queue.push({mask.countForeground(candidates[c].box), c});

    std::vector<FittedBox> chosen;
    std::int64_t remaining = mask.totalForeground();
    const std::int64_t total = std::max<std::int64_t>(remaining, 1);
    std::size_t pops = 0;
    while (!queue.empty() && remaining > 0) {
        if ((++pops & 1023) == 0) {
            control.checkCancel();
            if (control.progress)
                control.progress(
                    0.9 + 0.1 * (1.0 - static_cast<double>(remaining) / static_cast<double>(total)), "cover");
        }
        const auto [weight, c] = queue.top();
        queue.pop();
        const std::int64_t fresh = countUncovered(candidates[c].box);
        if (fresh == 0) continue;
        // Lazy greedy: a weight only ever drops, so if the fresh one still beats the next stale one, take it.
        if (!queue.empty() && fresh < queue.top().first) {
            queue.push({fresh, c});
            continue;
        }
        const Box& b = candidates[c].box;
        for (int k = b.lo[2]; k < b.hi[2]; ++k)
            for (int j = b.lo[1]; j < b.hi[1]; ++j)
                for (int i = b.lo[0]; i < b.hi[0]; ++i)
                    covered[cellIndex(i, j, k)] = 1;
        remaining -= fresh;
        chosen.push_back(candidates[c]);
        (void)weight;
    }
    return chosen;
}

} // namespace vots::fit
