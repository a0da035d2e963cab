// The order in which Vot records are stored on the GPU: it decides which records share cache lines.
#pragma once

#include "vots/fit/Vot.h"
#include "vots/render/GpuLayout.h"

#include <cstddef>
#include <vector>

namespace vots::render {

/// Z-order (Morton) of the boxes' low corners: Vots near each other in space are near in memory, so the
/// walk, which reads the records of the Vots along neighbouring rays, touches few cache lines
/// (bench/RESULTS.md compares it with bound order). Ties keep file order.
std::vector<std::size_t> spatialOrder(const std::vector<fit::Vot>& vots);

/// Descending upper bound (GpuVot::upperBound, the one culling compares), ties in the records' order: what
/// Raster's batch culling and the splat want, since the brightest Vots drawn first let later ones be
/// culled.
std::vector<std::size_t> boundOrder(const std::vector<GpuVot>& vots);

} // namespace vots::render
