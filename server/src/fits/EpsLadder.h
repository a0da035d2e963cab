// The eps the viewer's slider offers for a dataset: round percentages of its value range, and its default.
#pragma once

#include "datasets/DatasetRegistry.h"

#include <cstddef>
#include <optional>
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

/// The rung a viewer's drafts at `eps` are drawn from while the camera moves: the one nearest
/// DRAFT_EPS_FACTOR x eps, at most DRAFT_EPS_CAP of the range (`span`). A splat frame's cost falls with
/// the Vots a ray meets, so a draft from a coarser fit is about twice as cheap per pixel and is drawn
/// larger in the same time (bench/RESULTS.md, "Drafts from the draft rung"); the still after the drag is
/// drawn at eps itself. nullopt when no rung is at least DRAFT_EPS_LEAST x eps: not worth a second fit.
std::optional<double> draftRung(const std::vector<double>& ladder, double eps, double span);

/// The draft rung's eps over the still's: at 4x the Cranium's splat draws a pixel twice as fast, at 8x
/// only 1.3x faster again (the frame's fixed costs), with the Vots' streaks plain along every edge.
inline constexpr double DRAFT_EPS_FACTOR = 4.0;
/// Of the value range: past it the Vots grow blocky enough to show in a moving frame.
inline constexpr double DRAFT_EPS_CAP = 0.1;
/// A rung less coarse than this over eps would save too little to be worth a second fit and upload.
inline constexpr double DRAFT_EPS_LEAST = 1.5;

} // namespace vots::server
