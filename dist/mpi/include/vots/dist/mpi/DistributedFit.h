// `vots fit` under mpirun: each rank fits the planes of its z cells; what their fits add up to.
#pragma once

#include "vots/dist/RankCells.h"
#include "vots/dist/mpi/MpiWorld.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Volume.h"

#include <cstdint>

namespace vots::dist {

/// This rank's cells of a volume of `planesZ` z planes. Throws InputError for fewer than 2 planes or more
/// ranks than z cells (a rank without a cell would have nothing to fit).
RankCells fitCellsOfRank(const MpiWorld& world, std::uint64_t planesZ);

/// Moves this rank's fit of its cells' planes into the grid of `whole` (its Vots stay with it) and gives
/// every rank the file's view of the whole fit: the highest degree, the summed counters, the whole
/// volume's background fill (wholeVolumeFill), the largest error and the longest fit time. Returns the
/// Vots of all ranks. A collective.
std::uint64_t reduceFitOverRanks(const MpiWorld& world, fit::FitResult& result, RankCells cells,
                                 const fit::Volume& whole);

} // namespace vots::dist
