// Private: sample type sizes and spellings, size limits, and bytes -> float decoding for every reader.
#pragma once

#include "vots/fit/PatientAxes.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include "InputFile.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// Sanity caps: beyond these a header is taken to be lying (or the volume is not for this tool).
inline constexpr std::uint64_t MAX_SAMPLES = std::uint64_t{1} << 31;
inline constexpr std::uint64_t MAX_PAYLOAD_BYTES = std::uint64_t{16} << 30;

/// Grid dimensions that passed the checks, with the payload size they imply.
struct CheckedShape {
    std::array<int, 3> dims{0, 0, 0};
    std::size_t samples = 0;
    std::size_t bytes = 0;
};

std::size_t scalarTypeSize(ScalarType type);

/// Every spelling we accept ("uint8", "uchar", "unsigned char", "short", "float32", "double", ...),
/// case-insensitive; nullopt when unknown.
std::optional<ScalarType> findScalarType(const std::string& text);

/// A volume's grid without samples, as a header states it; `axes` nullopt: orientation unknown.
Volume gridWithoutSamples(const std::array<int, 3>& dims, const std::array<double, 3>& spacing,
                          const std::array<double, 3>& origin, const std::optional<PatientAxes>& axes,
                          ScalarType type, std::string name);

/// gridWithoutSamples of a parsed header (NiftiInfo, MghInfo: shape, spacing, origin, axes, type), named
/// after the file.
template <class HeaderInfo> Volume gridOfHeader(const std::string& path, const HeaderInfo& info) {
    return gridWithoutSamples(info.shape.dims, info.spacing, info.origin, info.axes, info.type,
                              fileStem(path));
}

/// Checks that each dimension is positive and the sample count and byte size stay under the caps.
CheckedShape checkShape(const std::string& path, const std::array<long long, 3>& dims, ScalarType type);

/// The value with its bytes in reverse order (to read data of the other endianness).
template <typename U> U byteSwapped(U value) {
    U out = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) {
        out = static_cast<U>((out << 8) | (value & 0xFF));
        value = static_cast<U>(value >> 8);
    }
    return out;
}

/// Decodes `count` samples stored as `type` with the given byte order. NaN and Inf stay (no data); a
/// double beyond float range becomes an infinity.
std::vector<float> decodeSamples(const unsigned char* bytes, std::size_t count, ScalarType type,
                                 bool bigEndian);

/// True when `storage` keeps samples of `type` in Volume::compact.
bool keepsCompact(ScalarType type, SampleStorage storage);

/// Fills volume.values or volume.compact (as keepsCompact says) from the file's bytes.
void storeSamples(Volume& volume, const unsigned char* bytes, std::size_t count, ScalarType type,
                  bool bigEndian, SampleStorage storage);

/// Writes exactly the payload (the file's bytes of all samples) at `destination`.
using PayloadReader = std::function<void(unsigned char* destination)>;

/// As storeSamples, but the payload is read straight into the samples' own memory and decoded there,
/// so loading never holds the volume twice (float64 files, narrowed to float, are the exception).
/// Only for payloads whose size the file has already proven: the memory is taken before reading.
void readSamples(Volume& volume, std::size_t count, ScalarType type, bool bigEndian, SampleStorage storage,
                 const PayloadReader& read);

} // namespace vots::fit::detail
