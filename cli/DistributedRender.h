// `vots render` under mpirun: each rank holds the Vots of its slab of the grid's z cells; the ranks' float
// frames are composited on rank 0 (docs/DESIGN.md, "Across hosts").
#pragma once

#include "MpiWorld.h"
#include "ZSlab.h"

#include "vots/fit/VotSpace.h"
#include "vots/render/CellDomain.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"

#include <array>
#include <chrono>
#include <vector>

namespace vots::cli {

/// True for the projections whose ranks cut their rays to their own slab of cells (minip, aip): they
/// take background and lengths along the ray, which another rank's cells must not add to. The max and
/// the density take whole rays, and need no cut.
bool compositesCutRays(render::RenderMode mode);

/// The Vots a rank draws: for whole rays, those whose box starts in the slab (in a Vot-Space of disjoint
/// boxes each Vot lies on one rank, so the max, or min, over the ranks' frames is the frame of the whole
/// Vot-Space, bit for bit); for rays cut to the slab, every Vot whose box meets it, so that each of the
/// slab's cells is covered on its rank as it is in the whole.
fit::VotSpace votsOfSlab(fit::VotSpace space, ZSlab slab, bool cutRays);

/// The slab's cells as the walk's domain, on a grid of `dims` points.
render::CellDomain cellDomainOfSlab(ZSlab slab, const std::array<int, 3>& dims);

/// The per-pixel arithmetic of every composite of the Vots' frames, shared by the collectives below
/// (`vots render`) and FrameComposite (`vots serve`, one rank's frame at a time), so both give the same
/// bits. MinIP: a rank whose cut ray takes nothing has -inf, which must not win the min: it is +inf while
/// the ranks' frames combine (minIpForCombining), and turned back after (minIpFromCombined).
void minIpForCombining(std::vector<float>& pixels);
void minIpFromCombined(std::vector<float>& pixels);
/// Element-wise max (mip) or min (minip in its combining form, density) of `other` into `into`.
void combineExtremes(render::RenderMode mode, std::vector<float>& into, const std::vector<float>& other);
/// The aip: adds one rank's integrals (mean x length, exact in double) and lengths to `sums` (2 x pixels:
/// the integrals, then the lengths), skipping pixels whose ray misses the rank's cells; throws
/// std::runtime_error when the sizes disagree.
void addMeanParts(std::vector<double>& sums, const render::FloatImage& means,
                  const render::FloatImage& lengths);
/// sum(integrals) / sum(lengths) per pixel into `means`, -inf where no rank's ray has any length.
void meansFromParts(const std::vector<double>& sums, render::FloatImage& means);

/// Composites the ranks' float frames of one projection onto rank 0: max for mip, min for density and
/// minip (whose ranks' rays are cut to their slabs). The aip goes through compositeMeansOnRoot.
void compositeOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame);

/// The aip composited onto rank 0: per pixel sum(mean_r x length_r) / sum(length_r) over the ranks, each
/// rank's mean and length taken inside its slab of cells (VotRenderer::rayLengths); -inf where no rank's
/// ray has any length, as one process gives where the ray misses.
void compositeMeansOnRoot(const MpiWorld& world, render::FloatImage& means,
                          const render::FloatImage& lengths);

/// The exact grid's frames composited onto rank 0: each rank draws its slab of cells with the whole ray's
/// length (GridRenderer::uploadSlab), so the frame of the whole is the max (mip), the min (minip: +inf
/// where a rank's ray takes nothing, as where one process's misses) or the sum (aip) of the ranks' frames.
void compositeGridOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame);

/// `vots render --times`: milliseconds since `start`, the slowest rank's (every rank must call it: it
/// waits for them all, so the next step's time is its own).
double slowestRankMillisSince(const MpiWorld& world, std::chrono::steady_clock::time_point start);
/// Rank 0 prints the frame's split on stderr: "vots render: N rank(s), render R ms, composite C ms".
void reportFrameTimes(const MpiWorld& world, double renderMs, double compositeMs);

} // namespace vots::cli
