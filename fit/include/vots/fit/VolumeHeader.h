// What a volume file announces in its header (grid size, stored sample type), read without its samples.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace vots::fit {

/// The announced grid, as the header states it: no size caps applied, so a header that lies about a
/// huge volume is reported as huge (and refused by the memory budget) rather than loaded.
struct VolumeHeaderInfo {
    std::array<std::uint64_t, 3> dims{0, 0, 0};
    ScalarType sourceType = ScalarType::UInt8;
    /// NIfTI scl_slope/scl_inter apply: the samples load as floats, whatever sourceType says.
    bool scaled = false;
    /// 3D volumes in the file (a 4D NIfTI or MGH file holds several); dims and sizes are of one.
    std::uint64_t frames = 1;

    /// dims[0] * dims[1] * dims[2], saturating at UINT64_MAX instead of wrapping.
    std::uint64_t sampleCount() const;
    /// Bytes of the samples as the file stores them (decompressed), saturating.
    std::uint64_t storedBytes() const;
    /// "256x256x108 int16".
    std::string describe() const;
};

/// Reads only the header (a few KB; for .nii.gz and .mgz the header's inflated bytes), never the samples, so
/// it costs the same for any announced size. The format follows the extension as in loadVolume; with a raw
/// layout the layout is the answer. Throws InputError for a header loadVolume would refuse as malformed
/// (unknown format, missing or non-positive sizes, unsupported type or dimension). A folder is a DICOM
/// series: the headers of its files (never their pixel data) give the grid and the type it loads into.
VolumeHeaderInfo volumeHeaderInfo(const std::string& path, const std::optional<RawLayout>& raw = std::nullopt,
                                  const std::string& dicomSeries = {});

} // namespace vots::fit
