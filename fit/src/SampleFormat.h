// Private: what a volume file's header says of its samples, whether they lie stored or gzip-compressed.
#pragma once

#include "SampleDecode.h"

#include "vots/fit/Volume.h"

#include <cstddef>
#include <cstdint>

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

/// Where the planes of `planes` (the grid gridOfPlanes cut from `format.grid`, from plane `first`) lie in
/// the payload: `count` samples of `sampleBytes` bytes each, from byte `from`.
struct PayloadRange {
    std::size_t count = 0;
    std::size_t sampleBytes = 0;
    std::uint64_t from = 0;
};
inline PayloadRange payloadRangeOf(const SampleFormat& format, const Volume& planes, int first) {
    const std::size_t plane =
        static_cast<std::size_t>(format.grid.dims[0]) * static_cast<std::size_t>(format.grid.dims[1]);
    PayloadRange range;
    range.count = plane * static_cast<std::size_t>(planes.dims[2]);
    range.sampleBytes = scalarTypeSize(format.type);
    range.from = static_cast<std::uint64_t>(plane) * static_cast<std::uint64_t>(first) * range.sampleBytes;
    return range;
}

} // namespace vots::fit::detail
