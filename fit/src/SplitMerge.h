// The fast generator: top-down split of zones until each box fits, then merge of face-sharing boxes.
#pragma once

#include "BoxTester.h"
#include "CellMask.h"

#include <functional>
#include <vector>

namespace vots::fit {

struct FitControl {
    int threads = 1;
    std::function<void(double, const char*)> progress;
    const std::atomic<bool>* cancel = nullptr;
    void checkCancel() const {
        if (cancel && cancel->load(std::memory_order_relaxed)) throw FitCancelled();
    }
};

/// The split starts from zones: the cell grid cut into cubes of ZONE_CELLS^3 cells (smaller at the far
/// edges), each split and merged on its own thread before the merge across zone planes.
inline constexpr int ZONE_CELLS = 32;
static_assert(ZONE_CELLS == 1 << FitCache::Impl::SHARD_CELLS_LOG2, "a zone's boxes share one cache shard");

/// Splits every zone that holds foreground cells; the leaves partition the foreground cells.
std::vector<FittedBox> splitZones(const CellMask& mask, const BoxTester& tester, const FitControl& control);

/// Merges pairs of boxes that share a whole face when their union fits; boxes stay disjoint.
/// zoneCells > 0 says the boxes were already merged zone by zone (zones of that many cells, as
/// splitZones does): every pair inside one zone has been tried, so only boxes with a face on a zone
/// plane start the work, and of those boxes only the faces on a zone plane are tried. The result is
/// the same as trying every face of every box, without re-testing those pairs (a fresh fit has no cache
/// to answer them; test_SplitMerge.cpp checks the equivalence).
void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control,
                     int zoneCells = 0);

} // namespace vots::fit
