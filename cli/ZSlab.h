// Under mpirun each rank holds one slab of the grid's z cells: which, its planes, and its Vots' place.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"
#include "vots/fit/VotSpace.h"

#include <optional>
#include <string>

namespace vots::cli {

/// Cells [first, end) along z: rank r of n takes cells [r C / n, (r + 1) C / n) of the C = dims z - 1.
struct ZSlab {
    int first = 0;
    int end = 0;
    bool empty() const { return end <= first; }
};
ZSlab zSlabOfRank(int cellsZ, int rank, int ranks);

/// Planes [first, end] of the volume: the slab's cells, with the plane they share with the next slab.
fit::Volume planesOfSlab(const fit::Volume& volume, ZSlab slab);
/// The same planes read from the file, only their bytes where the format allows (fit::loadVolumePlanes),
/// with the whole volume's grid.
fit::VolumeSlab loadSlab(const std::string& path, ZSlab slab, const std::optional<fit::RawLayout>& raw,
                         fit::SampleStorage storage, const std::string& dicomSeries);
/// Moves a Vot-Space fitted on the slab's planes into the grid of the whole (`whole`: its grid is enough).
void placeSlabFitInGrid(fit::VotSpace& space, ZSlab slab, const fit::Volume& whole);

} // namespace vots::cli
