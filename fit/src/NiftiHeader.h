// Private: NIfTI-1 and NIfTI-2 headers (either byte order) read into one form, and what they say.
#pragma once

#include "vots/fit/PatientAxes.h"
#include "vots/fit/Volume.h"

#include "SampleDecode.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace vots::fit::detail {

inline constexpr std::size_t NIFTI1_HEADER_BYTES = 348;
inline constexpr std::size_t NIFTI2_HEADER_BYTES = 540;

/// The header's size (348: NIfTI-1, 540: NIfTI-2) from its first 4 bytes, sizeof_hdr in either byte
/// order; throws InputError for anything else.
std::size_t niftiHeaderBytes(const std::string& path, const unsigned char* first4);

/// The header fields the readers use, as the file states them (NIfTI-1's int16 and float fields widened).
struct NiftiFields {
    int version = 1;   // 1 or 2
    bool swap = false; // the file's byte order is not the host's
    std::array<std::int64_t, 8> dim{};
    int datatype = 0;
    int bitpix = 0;
    std::array<double, 8> pixdim{};
    double voxOffset = 0.0;
    double slope = 0.0;
    double inter = 0.0;
    int qformCode = 0;
    int sformCode = 0;
    std::array<double, 3> quatern{};             // b, c, d
    std::array<double, 3> qoffset{};             // x, y, z
    std::array<std::array<double, 4>, 3> srow{}; // srow_x, srow_y, srow_z
    std::array<char, 4> magic{};                 // "n+1", "ni1", "n+2", ...
};

/// Reads the fields of a whole header (niftiHeaderBytes of them at `bytes`).
NiftiFields readNiftiFields(const std::string& path, const unsigned char* bytes);

/// The NIfTI datatype code as our type; throws InputError for an unsupported one.
ScalarType niftiType(const std::string& path, int datatype);

/// 3D volumes in the file: the product of dim[4..dim[0]] (1 for a 3D file); throws for a rank outside
/// 3..7, a non-positive extra dimension or a count beyond the sample cap.
std::uint64_t niftiFrames(const std::string& path, const NiftiFields& fields);

/// What the header says, checked: the grid of one frame and where the frames lie.
struct NiftiInfo {
    CheckedShape shape; // of one frame
    std::uint64_t frames = 1;
    ScalarType type = ScalarType::UInt8;
    bool bigEndian = false;
    std::uint64_t voxOffset = 0;
    double slope = 0.0; // 0: no scaling
    double inter = 0.0;
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    std::optional<PatientAxes> axes; // in LPS; nullopt: neither sform nor qform (NIfTI method 1)
};

/// Checks and interprets a whole header; throws InputError with a one-line message.
NiftiInfo parseNiftiHeader(const std::string& path, const unsigned char* bytes);

/// The byte offset of frame `frame`'s samples; throws InputError (naming the frame count) when the file
/// holds no such frame.
std::uint64_t frameOffset(const std::string& path, const NiftiInfo& info, int frame);

} // namespace vots::fit::detail
