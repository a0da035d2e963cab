// The fast generator: top-down split of zones until each box fits, then merge of face-sharing boxes.
#pragma once

#include "BoxTester.h"
#include "CellMask.h"

#include <array>
#include <functional>
#include <vector>

namespace vots::fit {

struct FitControl {
    int threads = 1;
    FitProgress progress;
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

/// The same with planes per axis: planeCells[a] > 0 says every pair of boxes not separated by a plane
/// at a multiple of planeCells[a] along some axis a has been tried; 0 on an axis: no such planes.
void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control,
                     const std::array<int, 3>& planeCells);

/// splitZones' boxes are merged across zone planes in bands of this many cells along z, each band on
/// a thread of its own, and then across the band planes only: the merge across zones no longer runs on
/// one thread (bench/RESULTS.md, "512x512x1000 under mpirun"). Fixed, not taken from the thread count,
/// so that a fit's boxes never depend on how many threads made them.
inline constexpr int MERGE_BAND_CELLS = 4 * ZONE_CELLS;

/// Merges splitZones' boxes across zone planes: band by band in parallel, then across band planes.
void mergeAcrossZones(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control);

} // namespace vots::fit
