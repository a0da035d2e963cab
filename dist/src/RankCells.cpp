// The z cells each rank owns: their bounds, their planes, and the fit moved back into the grid.
#include "vots/dist/RankCells.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"

#include <algorithm>

namespace vots::dist {

RankCells cellsOfRank(int cellsZ, int rank, int ranks) {
    const auto at = [&](int r) { return static_cast<int>(static_cast<long long>(cellsZ) * r / ranks); };
    return {at(rank), at(rank + 1)};
}

RankCells cellsOfRankInVolume(const std::string& path, int rank, int ranks,
                              const std::optional<fit::RawLayout>& raw, const std::string& dicomSeries) {
    const auto planesZ = fit::volumeHeaderInfo(path, raw, dicomSeries).dims[2];
    if (planesZ < 2)
        throw fit::InputError("volume needs at least 2 grid points along every axis to form a cell");
    return cellsOfRank(static_cast<int>(planesZ) - 1, rank, ranks);
}

fit::Volume planesOfCells(const fit::Volume& volume, RankCells cells) {
    return fit::planesOf(volume, cells.first, cells.end);
}

fit::PlanesOfGrid loadPlanesOfCells(const std::string& path, RankCells cells,
                                    const std::optional<fit::RawLayout>& raw, fit::SampleStorage storage,
                                    const std::string& dicomSeries, int frame) {
    return fit::loadVolumePlanes(path, cells.first, cells.end, raw, storage, dicomSeries, frame);
}

void placeCellsFitInGrid(fit::VotSpace& space, RankCells cells, const fit::Volume& whole) {
    for (fit::Vot& v : space.vots) {
        v.box.lo[2] += cells.first;
        v.box.hi[2] += cells.first;
        v.p[2] += static_cast<float>(cells.first);
    }
    space.dims = whole.dims;
    space.origin = whole.origin;
    space.spacing = whole.spacing;
    space.patientAxes = whole.patientAxes;
    space.orientationKnown = whole.orientationKnown;
}

fit::VotSpace votsOfCells(fit::VotSpace space, RankCells cells, bool cutRays) {
    std::erase_if(space.vots, [&](const fit::Vot& v) {
        if (cutRays) return v.box.lo[2] >= cells.end || v.box.hi[2] <= cells.first;
        return v.box.lo[2] < cells.first || v.box.lo[2] >= cells.end;
    });
    return space;
}

} // namespace vots::dist
