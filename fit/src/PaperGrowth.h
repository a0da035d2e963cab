// The paper's generator (docs/DESIGN.md §4, paper method): a seed at every foreground cell, grown, covered.
#pragma once

#include "BoxTester.h"
#include "CellMask.h"
#include "SplitMerge.h"

#include <vector>

namespace vots::fit {

/// One grown candidate per foreground cell (duplicates removed), each certified within eps.
std::vector<FittedBox> growSeeds(const CellMask& mask, const BoxTester& tester, const FitControl& control);

/// Lazy-greedy cover of the foreground cells (docs/DESIGN.md §4, paper method step 3): the chosen boxes.
std::vector<FittedBox> greedyCover(std::vector<FittedBox> candidates, const CellMask& mask,
                                   const FitControl& control);

} // namespace vots::fit
