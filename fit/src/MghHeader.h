// Private: FreeSurfer MGH headers (.mgh, and .mgz inflated), checked and interpreted.
#pragma once

#include "vots/fit/PatientAxes.h"
#include "vots/fit/Volume.h"

#include "SampleDecode.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace vots::fit::detail {

/// The samples start here, after the fixed header (its used fields and the unused rest).
inline constexpr std::size_t MGH_HEADER_BYTES = 284;

/// What an MGH header says: the grid of one frame, the frame count, and vox2ras as our grid.
struct MghInfo {
    CheckedShape shape; // of one frame
    std::uint64_t frames = 1;
    ScalarType type = ScalarType::UInt8;
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0}; // LPS
    PatientAxes axes{};                          // LPS
};

/// Checks and interprets the MGH_HEADER_BYTES at `bytes` (big-endian, as FreeSurfer writes them); throws
/// InputError with a one-line message.
MghInfo parseMghHeader(const std::string& path, const unsigned char* bytes);

} // namespace vots::fit::detail
