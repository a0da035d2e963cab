// Slabs of the grid's z cells per rank: their bounds, their planes, and the fit moved back into the grid.
#include "ZSlab.h"

namespace vots::cli {

ZSlab zSlabOfRank(int cellsZ, int rank, int ranks) {
    const auto at = [&](int r) { return static_cast<int>(static_cast<long long>(cellsZ) * r / ranks); };
    return {at(rank), at(rank + 1)};
}

fit::Volume planesOfSlab(const fit::Volume& volume, ZSlab slab) {
    return fit::planesOf(volume, slab.first, slab.end);
}

fit::VolumeSlab loadSlab(const std::string& path, ZSlab slab, const std::optional<fit::RawLayout>& raw,
                         fit::SampleStorage storage, const std::string& dicomSeries) {
    return fit::loadVolumePlanes(path, slab.first, slab.end, raw, storage, dicomSeries);
}

void placeSlabFitInGrid(fit::VotSpace& space, ZSlab slab, const fit::Volume& whole) {
    for (fit::Vot& v : space.vots) {
        v.box.lo[2] += slab.first;
        v.box.hi[2] += slab.first;
        v.p[2] += static_cast<float>(slab.first);
    }
    space.dims = whole.dims;
    space.origin = whole.origin;
    space.spacing = whole.spacing;
    space.patientAxes = whole.patientAxes;
    space.orientationKnown = whole.orientationKnown;
}

} // namespace vots::cli
