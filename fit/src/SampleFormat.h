// Private: what a volume file's header says of its samples, whether they lie stored or gzip-compressed.
#pragma once

#include "vots/fit/Volume.h"

namespace vots::fit::detail {

/// The grid (a Volume without samples), how each sample is stored and NIfTI's scaling: the part of
/// StoredSamples and GzipSamples that does not depend on where the payload lies.
struct SampleFormat {
    Volume grid;
    ScalarType type = ScalarType::UInt8;
    bool bigEndian = false;
    double slope = 0.0; // NIfTI scl_slope and scl_inter; slope 0: the samples are not scaled
    double inter = 0.0;
};

} // namespace vots::fit::detail
