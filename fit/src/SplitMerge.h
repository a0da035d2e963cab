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
void mergeNeighbours(std::vector<FittedBox>& boxes, const BoxTester& tester, const FitControl& control);

} // namespace vots::fit
