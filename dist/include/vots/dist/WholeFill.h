// The background fill of the whole volume from the ranks' fits of their cells: one arithmetic for
// `mpirun vots fit`, `mpirun vots render` and the frames `mpirun vots serve` draws.
#pragma once

#include "vots/fit/Fitter.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace vots::dist {

/// One rank's part of the fill: its fit's background cells and the sum of their values.
struct BackgroundSums {
    std::uint64_t cells = 0;
    double valueSum = 0.0;
};
BackgroundSums backgroundSumsOf(const fit::FitStats& stats);

/// fit::backgroundFillOf the ranks' sums, added in rank order (the ranks' cells split the volume's, so
/// the counts add up exactly); nullopt when no rank has a background cell.
std::optional<float> wholeVolumeFill(const std::vector<BackgroundSums>& ranks);

} // namespace vots::dist
