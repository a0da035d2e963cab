// Private: the smallest and largest finite sample of a run of a volume's samples, which valueRange and a
// reader summing up slices as they arrive (DicomSeriesIntake) both take.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <cstddef>

namespace vots::fit {

/// Smallest and largest finite sample of held samples [begin, end); lo > hi when there is none. NaN and
/// Inf samples are no data (docs/DESIGN.md §4 "Non-finite samples").
std::array<float, 2> finiteRange(const Volume& volume, std::size_t begin, std::size_t end);

/// A range as Volume::valueRange gives it: {0, 0} when lo > hi (no finite sample). The min and max of
/// runs' finiteRange, so made usable, is the volume's valueRange.
std::array<float, 2> usableRange(std::array<float, 2> range);

} // namespace vots::fit
