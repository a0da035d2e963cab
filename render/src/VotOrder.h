// The order in which Vot records are stored on the GPU: it decides which records share cache lines.
#pragma once

#include "VotBounds.h"

#include "vots/fit/Vot.h"

#include <cstddef>
#include <vector>

namespace vots::render {

/// Z-order (Morton) of the boxes' low corners: Vots near each other in space are near in memory, so the
/// walk, which reads the records of the Vots along neighbouring rays, touches few cache lines
/// (bench/RESULTS.md compares it with bound order). Ties keep file order.
std::vector<std::size_t> spatialOrder(const std::vector<fit::Vot>& vots);

/// Descending upper bound, ties in file order: what Raster's batch culling wants, since the brightest
/// Vots drawn first let later batches be culled.
std::vector<std::size_t> boundOrder(const std::vector<VotBounds>& bounds);

} // namespace vots::render
