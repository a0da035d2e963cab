// The fast generator: top-down split of bricks until each box fits, then merge of face-sharing boxes.
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

inline constexpr int BRICK_CELLS = 32;

/// Splits every brick that holds foreground cells; the leaves partition the foreground cells.
std::vector<FittedBox> splitBricks(const CellMask& mask, const BoxTester& tester, const FitControl& control);

/// Merges pairs of boxes that share a whole face when their union fits; boxes stay disjoint.
/// brickCells > 0 says the boxes were already merged brick by brick (bricks of that many cells, as
/// splitBricks does): every pair inside one brick has been tried, so only boxes with a face on a brick
/// plane start the work, and of those boxes only the faces on a brick plane are tried. The result is
/// the same as trying every face of every box, without re-testing those pairs (a fresh fit has no cache
/// to answer them; test_SplitMerge.cpp checks the equivalence).
void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control,
                     int brickCells = 0);

} // namespace vots::fit
