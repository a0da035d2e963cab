// `vots fit` under mpirun: z cells per rank, and what their fits add up to over the ranks.
#include "vots/dist/mpi/DistributedFit.h"

#include "vots/dist/WholeFill.h"

#include "vots/fit/Error.h"

#include <string>
#include <vector>

namespace vots::dist {

RankCells fitCellsOfRank(const MpiWorld& world, std::uint64_t planesZ) {
    if (planesZ < 2)
        throw fit::InputError("volume needs at least 2 grid points along every axis to form a cell");
    const std::uint64_t cellsZ = planesZ - 1;
    if (cellsZ < static_cast<std::uint64_t>(world.size()))
        throw fit::InputError("the volume has " + std::to_string(cellsZ) + " cells along z, fewer than the " +
                              std::to_string(world.size()) + " ranks: start at most " +
                              std::to_string(cellsZ) + " (each rank fits a range of z cells)");
    return cellsOfRank(static_cast<int>(cellsZ), world.rank(), world.size());
}

std::uint64_t reduceFitOverRanks(const MpiWorld& world, fit::FitResult& result, RankCells cells,
                                 const fit::Volume& whole) {
    fit::VotSpace& space = result.space;
    placeCellsFitInGrid(space, cells, whole);
    fit::FitStats& s = result.stats;
    // The fill first, from this rank's own counters: the whole volume's, as every distributed fit gives it.
    space.backgroundFill = wholeVolumeFill(world.gatherOnEveryRank(backgroundSumsOf(s)));
    const std::vector<std::uint64_t> sums = world.sumOverRanks(
        {s.boxFits, s.boxScans, s.cacheHits, s.coveredCells, s.backgroundCells, space.vots.size()});
    s.boxFits = sums[0];
    s.boxScans = sums[1];
    s.cacheHits = sums[2];
    s.coveredCells = sums[3];
    s.backgroundCells = sums[4];
    // The ranks' cells split the volume's, so the sums over their background cells add up exactly.
    s.backgroundValueSum = world.sumOverRanks(s.backgroundValueSum);
    s.seconds = world.maxOverRanks(s.seconds);
    s.maxError = world.maxOverRanks(s.maxError);
    space.degree = static_cast<int>(world.maxOverRanks(space.degree));
    return sums[5];
}

} // namespace vots::dist
