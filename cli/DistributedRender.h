// `vots render` under mpirun: each rank holds the Vots of its slab of the grid's z cells; the ranks'
// float frames are composited on rank 0 (docs/DESIGN.md, "Across hosts").
#pragma once

#include "MpiWorld.h"

#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"

namespace vots::cli {

/// Cells [first, end) along z: rank r of n takes cells [r C / n, (r + 1) C / n) of the C = dims z - 1.
struct ZSlab {
    int first = 0;
    int end = 0;
    bool empty() const { return end <= first; }
};
ZSlab zSlabOfRank(int cellsZ, int rank, int ranks);

/// The Vots whose box starts in the slab: in a Vot-Space of disjoint boxes each Vot lies on one rank, so
/// the max (or min) over the ranks' frames is the frame of the whole Vot-Space, bit for bit.
fit::VotSpace votsOfSlab(fit::VotSpace space, ZSlab slab);
/// Planes [first, end] of the volume: the slab's cells, with the plane they share with the next slab.
fit::Volume planesOfSlab(const fit::Volume& volume, ZSlab slab);
/// Moves a Vot-Space fitted on planesOfSlab(whole, slab) into the whole grid's index space.
void placeSlabFitInGrid(fit::VotSpace& space, ZSlab slab, const fit::Volume& whole);

/// Composites the ranks' float frames of one projection onto rank 0: max for mip, min for density.
/// MinIP and the average would count the cells other ranks hold as background: refused for now.
void compositeOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame);

} // namespace vots::cli
