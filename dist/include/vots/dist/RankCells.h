// Under mpirun each rank owns a range of the grid's z cells: which, its planes, and its Vots' place.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"
#include "vots/fit/VotSpace.h"

#include <array>
#include <optional>
#include <string>

namespace vots::dist {

/// Cells [first, end) along z: rank r of n owns cells [r C / n, (r + 1) C / n) of the C = dims z - 1.
struct RankCells {
    int first = 0;
    int end = 0;
    bool empty() const { return end <= first; }
    bool operator==(const RankCells&) const = default;
};
RankCells cellsOfRank(int cellsZ, int rank, int ranks);
/// The cells of a volume file of that rank: from the header alone. Throws fit::InputError for fewer than
/// 2 planes along z.
RankCells cellsOfRankInVolume(const std::string& path, int rank, int ranks,
                              const std::optional<fit::RawLayout>& raw = std::nullopt,
                              const std::string& dicomSeries = {});

/// Planes [first, end] of the volume: the cells', with the plane they share with the next rank's.
fit::Volume planesOfCells(const fit::Volume& volume, RankCells cells);
/// The same planes read from the file, only their bytes where the format allows (fit::loadVolumePlanes),
/// with the whole volume's grid; `frame` picks one 3D volume of a 4D file, as in fit::loadVolume.
fit::PlanesOfGrid loadPlanesOfCells(const std::string& path, RankCells cells,
                                    const std::optional<fit::RawLayout>& raw, fit::SampleStorage storage,
                                    const std::string& dicomSeries, int frame = 0);
/// Moves a Vot-Space fitted on the cells' planes into the grid of the whole (`whole`: its grid is enough).
void placeCellsFitInGrid(fit::VotSpace& space, RankCells cells, const fit::Volume& whole);

/// The Vots a rank draws: for whole rays, those whose box starts in its cells (in a Vot-Space of disjoint
/// boxes each Vot lies on one rank, so the max, or min, over the ranks' frames is the frame of the whole
/// Vot-Space, bit for bit); for rays cut to its cells, every Vot whose box meets them, so that each of its
/// cells is covered on its rank as it is in the whole.
fit::VotSpace votsOfCells(fit::VotSpace space, RankCells cells, bool cutRays);

} // namespace vots::dist
