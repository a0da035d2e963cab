// The eps the viewer's slider offers for a dataset: round percentages of its value range, and its default.
#pragma once

#include "datasets/DatasetRegistry.h"

#include <cstddef>
#include <vector>

namespace vots::server {

/// A slider of ~1000 positions offered that many eps, each a new fit a move could not have prepared. The
/// ladder offers the E24 series of percentages of the value range (about 10 % apart, 24 to the decade),
/// few enough that the server fits the rungs around the shown one while idle (WarmUpFits) and a move to
/// one of them is a cache hit. Ascending; from 0.1 % to 50 % of the range, each in data units at three
/// significant digits (short URLs), the rung nearest the dataset's default replaced by the default. Empty
/// for a Vot-Space file (its one eps) and a dataset whose range is empty. Doubles, so that JSON writes
/// "88.2" rather than the float's 88.19999694824219; a fit key takes the float nearest each, as it does
/// of the text a viewer sends back.
std::vector<double> epsLadder(const Dataset& dataset);

/// Up to `count` rungs nearest `eps`, nearest first on a log scale (above first on a tie): the moves of a
/// hand on the slider, either way. `eps` itself (a rung within 0.1 % of it) is left out.
std::vector<double> rungsAround(const std::vector<double>& ladder, double eps, std::size_t count);

} // namespace vots::server
