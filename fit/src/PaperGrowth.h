// The paper's generator (DESIGN §4 steps 1-2): a cell seed at every foreground cell, grown face by face.
#pragma once

#include "BoxTester.h"
#include "CellMask.h"
#include "SplitMerge.h"

#include <vector>

namespace vots::fit {

/// One grown candidate per foreground cell (duplicates removed), each certified within eps.
std::vector<FittedBox> growSeeds(const CellMask& mask, const BoxTester& tester, const FitControl& control);

/// DESIGN §4 step 3: lazy-greedy cover of the foreground cells; returns the chosen candidates.
std::vector<FittedBox> greedyCover(std::vector<FittedBox> candidates, const CellMask& mask,
                                   const FitControl& control);

} // namespace vots::fit
