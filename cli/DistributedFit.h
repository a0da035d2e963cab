// `vots fit` under mpirun: each rank fits the planes of its z slab; the ranks write one file together.
#pragma once

#include "MpiWorld.h"
#include "ZSlab.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Volume.h"

#include <array>
#include <cstdint>
#include <string>

namespace vots::cli {

/// This rank's slab of a volume of `planesZ` z planes. Throws InputError for fewer than 2 planes or more
/// ranks than z cells (a rank without a cell would have nothing to fit).
ZSlab fitSlabOfRank(const MpiWorld& world, std::uint64_t planesZ);

/// Moves this rank's fit of its slab's planes into the grid of `whole` (its Vots stay with it) and gives
/// every rank the file's view of the whole fit: the highest degree, the summed counters, the background
/// fill, the largest error and the longest fit time. Returns the Vots of all ranks. A collective.
std::uint64_t reduceFitOverRanks(const MpiWorld& world, fit::FitResult& result, ZSlab slab,
                                 const fit::Volume& whole);

/// The meta block of a fit under mpirun: `meta` (built for the whole volume's grid, which holds no
/// samples) with the whole volume's value range and "ranks": the number of ranks that fitted it.
std::string metaOfRanks(const std::string& meta, std::array<float, 2> range, int ranks);

} // namespace vots::cli
