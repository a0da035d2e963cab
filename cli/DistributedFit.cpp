// `vots fit` under mpirun: slabs of z cells per rank, and what their fits sum up to over the ranks.
#include "DistributedFit.h"

#include "vots/fit/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <utility>
#include <vector>

namespace vots::cli {

ZSlab fitSlabOfRank(const MpiWorld& world, std::uint64_t planesZ) {
    if (planesZ < 2)
        throw fit::InputError("volume needs at least 2 grid points along every axis to form a cell");
    const std::uint64_t cellsZ = planesZ - 1;
    if (cellsZ < static_cast<std::uint64_t>(world.size()))
        throw fit::InputError("the volume has " + std::to_string(cellsZ) + " cells along z, fewer than the " +
                              std::to_string(world.size()) + " ranks: start at most " +
                              std::to_string(cellsZ) + " (each rank fits a slab of z cells)");
    return zSlabOfRank(static_cast<int>(cellsZ), world.rank(), world.size());
}

std::uint64_t reduceFitOverRanks(const MpiWorld& world, fit::FitResult& result, ZSlab slab,
                                 const fit::Volume& whole) {
    fit::VotSpace& space = result.space;
    placeSlabFitInGrid(space, slab, whole);
    fit::FitStats& s = result.stats;
    const std::vector<std::uint64_t> sums = world.sumOverRanks(
        {s.boxFits, s.boxScans, s.cacheHits, s.coveredCells, s.backgroundCells, space.vots.size()});
    s.boxFits = sums[0];
    s.boxScans = sums[1];
    s.cacheHits = sums[2];
    s.coveredCells = sums[3];
    s.backgroundCells = sums[4];
    // The ranks' slabs split the cells, so the sums over their background cells add up exactly.
    s.backgroundValueSum = world.sumOverRanks(s.backgroundValueSum);
    space.backgroundFill = fit::backgroundFillOf(s);
    s.seconds = world.maxOverRanks(s.seconds);
    s.maxError = world.maxOverRanks(s.maxError);
    space.degree = static_cast<int>(world.maxOverRanks(space.degree));
    return sums[5];
}

std::string metaOfRanks(const std::string& meta, std::array<float, 2> range, int ranks) {
    // Ordered: the keys stay where buildFitMeta put them, "ranks" comes last.
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(meta);
    j["source"]["value_range"] = {range[0], range[1]};
    j["ranks"] = ranks;
    return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

} // namespace vots::cli
