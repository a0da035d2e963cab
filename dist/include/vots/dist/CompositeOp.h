// The one table of how the ranks' float frames combine into the frame of the whole, and its arithmetic:
// shared by the collective composite (`vots render`) and the incremental one (`vots serve`).
#pragma once

#include "vots/dist/RankCells.h"

#include "vots/render/CellDomain.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"

#include <array>
#include <vector>

namespace vots::dist {

/// What a rank draws its part from: its Vots, or its planes with the exact grid renderer.
enum class RankSource { Vots, Grid };

/// How the ranks' frames of one projection combine, per pixel.
enum class CompositeOp {
    Max,          // mip
    Min,          // the density (the smallest box; +inf, no box, never wins), the grid's minip
    MinOfCutRays, // the Vots' minip: -inf (a ray cut to a rank's cells that takes nothing) never wins
    WeightedMean, // the Vots' aip: sum(mean x length) / sum(length) over the ranks' cut rays
    Sum,          // the grid's aip: each rank's part is already divided by the whole ray's length
};

/// The table: (render mode x what the ranks draw from) -> operation. Throws std::logic_error for the
/// grid's density, which the grid does not draw.
CompositeOp compositeOpFor(render::RenderMode mode, RankSource source);

/// True for the projections whose ranks cut their rays to their own cells (the Vots' minip and aip): they
/// take background and lengths along the ray, which another rank's cells must not add to. The max and
/// the density take whole rays, and need no cut.
bool compositesCutRays(render::RenderMode mode);
/// A rank's cells as the walk's domain its rays are cut to, on a grid of `dims` points.
render::CellDomain cutRayDomainOf(RankCells cells, const std::array<int, 3>& dims);

/// MinOfCutRays: a rank's -inf must not win the min: it is +inf while the frames combine
/// (minOfCutRaysForCombining), and turned back after (minOfCutRaysFromCombined).
void minOfCutRaysForCombining(std::vector<float>& pixels);
void minOfCutRaysFromCombined(std::vector<float>& pixels);
/// Element-wise max (Max) or min (Min, MinOfCutRays in its combining form) of `other` into `into`; throws
/// std::runtime_error when the sizes differ, std::logic_error for the sums.
void combineExtremes(CompositeOp op, std::vector<float>& into, const std::vector<float>& other);
/// WeightedMean: adds one rank's integrals (mean x length, exact in double) and lengths to `sums` (2 x
/// pixels: the integrals, then the lengths), skipping pixels whose ray misses the rank's cells; throws
/// std::runtime_error when the sizes disagree.
void addMeanParts(std::vector<double>& sums, const render::FloatImage& means,
                  const render::FloatImage& lengths);
/// sum(integrals) / sum(lengths) per pixel into `means`, -inf where no rank's ray has any length.
void meansFromParts(const std::vector<double>& sums, render::FloatImage& means);
/// Sum: adds one rank's frame to `sums` (in double: the ranks' parts round once, at the end).
void addSumPart(std::vector<double>& sums, const std::vector<float>& part);
/// The sums rounded to float into `frame`.
void sumsToFrame(const std::vector<double>& sums, render::FloatImage& frame);

} // namespace vots::dist
