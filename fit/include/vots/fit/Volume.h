// A sampled scalar field on a rectilinear grid, with its index-to-world transform; no file I/O here.
#pragma once

#include "vots/fit/EnumNames.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace vots::fit {

/// Sample type of the source file.
enum class ScalarType { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };

/// Our names first, then the NRRD spellings (teem's list) and C names the readers accept, each in the form
/// the readers normalise a header's text to (lower case, single spaces).
inline constexpr auto SCALAR_TYPE_NAMES =
    nameTable<ScalarType>("sample type", {{ScalarType::UInt8, "uint8"},
                                          {ScalarType::Int8, "int8"},
                                          {ScalarType::UInt16, "uint16"},
                                          {ScalarType::Int16, "int16"},
                                          {ScalarType::UInt32, "uint32"},
                                          {ScalarType::Int32, "int32"},
                                          {ScalarType::Float32, "float32"},
                                          {ScalarType::Float64, "float64"},
                                          {ScalarType::UInt8, "uint8_t"},
                                          {ScalarType::UInt8, "uchar"},
                                          {ScalarType::UInt8, "unsigned char"},
                                          {ScalarType::Int8, "int8_t"},
                                          {ScalarType::Int8, "char"},
                                          {ScalarType::Int8, "signed char"},
                                          {ScalarType::UInt16, "uint16_t"},
                                          {ScalarType::UInt16, "ushort"},
                                          {ScalarType::UInt16, "unsigned short"},
                                          {ScalarType::UInt16, "unsigned short int"},
                                          {ScalarType::Int16, "int16_t"},
                                          {ScalarType::Int16, "short"},
                                          {ScalarType::Int16, "short int"},
                                          {ScalarType::Int16, "signed short"},
                                          {ScalarType::Int16, "signed short int"},
                                          {ScalarType::UInt32, "uint32_t"},
                                          {ScalarType::UInt32, "uint"},
                                          {ScalarType::UInt32, "unsigned int"},
                                          {ScalarType::Int32, "int32_t"},
                                          {ScalarType::Int32, "int"},
                                          {ScalarType::Int32, "signed int"},
                                          {ScalarType::Float32, "float"},
                                          {ScalarType::Float64, "double"}});
constexpr const auto& namesOf(ScalarType) {
    return SCALAR_TYPE_NAMES;
}

inline std::string scalarTypeName(ScalarType type) {
    return std::string(nameOf(type));
}

/// Samples of an 8- or 16-bit integer file held in the file's own type: a half or a quarter of the
/// memory of floats, with the same values (float holds all of them exactly). Empty: `values` holds them.
using CompactSamples = std::variant<std::monostate, std::vector<std::uint8_t>, std::vector<std::int8_t>,
                                    std::vector<std::uint16_t>, std::vector<std::int16_t>>;

struct Volume {
    std::array<int, 3> dims{0, 0, 0};             // grid points along x, y, z
    std::array<double, 3> spacing{1.0, 1.0, 1.0}; // world distance between grid points (mm for CT)
    std::array<double, 3> origin{0.0, 0.0, 0.0};  // world position of grid point (0,0,0)
    /// Unit vector in patient coordinates (DICOM's LPS: +x the patient's left, +y posterior, +z superior)
    /// along which each grid index grows: patientAxes[0] for x, [1] for y, [2] for z. Only meaningful when
    /// `orientationKnown`; a file that says nothing (raw, NRRD without `space`) renders in index space.
    std::array<std::array<double, 3>, 3> patientAxes{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    bool orientationKnown = false;
    ScalarType sourceType = ScalarType::Float32; // what the file stored
    std::string name;                            // short label (file stem), for meta data and logs
    std::vector<float> values;                   // x fastest, then y, then z; empty when compact
    CompactSamples compact;                      // the samples instead of `values` (same order)

    std::size_t sampleCount() const {
        return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
               static_cast<std::size_t>(dims[2]);
    }
    std::size_t indexOf(int x, int y, int z) const {
        return static_cast<std::size_t>(x) +
               static_cast<std::size_t>(dims[0]) *
                   (static_cast<std::size_t>(y) +
                    static_cast<std::size_t>(dims[1]) * static_cast<std::size_t>(z));
    }
    bool isCompact() const { return !std::holds_alternative<std::monostate>(compact); }
    /// Samples held, in `values` or `compact`.
    std::size_t heldSamples() const;
    float at(int x, int y, int z) const {
        if (!isCompact()) return values[indexOf(x, y, z)];
        return std::visit(
            [i = indexOf(x, y, z)](const auto& held) -> float {
                if constexpr (std::is_same_v<std::decay_t<decltype(held)>, std::monostate>)
                    return 0.0f;
                else
                    return static_cast<float>(held[i]);
            },
            compact);
    }

    /// Smallest and largest finite sample value; {0,0} for a volume without one. NaN and Inf samples are
    /// no data (docs/DESIGN.md §4 "Non-finite samples"): every part of a fit skips them.
    std::array<float, 2> valueRange() const;
    /// How many samples are NaN or Inf.
    std::size_t nonFiniteCount() const;
    /// CRC-32 of the grid (dims, spacing, origin) and every sample as float, whichever way it is held:
    /// tells a changed file from the one a cached fit was made of.
    std::uint32_t contentCrc() const;
    /// The part of contentCrc before the samples: of dims, spacing and origin.
    std::uint32_t gridCrc() const;
    /// CRC-32 (from 0) of `count` z planes from plane `first` as floats: contentCrc's samples in runs, so
    /// that processes holding different planes can give the whole volume's CRC together (combineCrc).
    std::uint32_t planesCrc(int first, int count) const;
};

/// The CRC-32 of bytes A then B from crc(A), crc(B) and B's length (zlib's crc32_combine): chained from
/// gridCrc over a volume's planesCrc runs in z order, it is the volume's contentCrc.
std::uint32_t combineCrc(std::uint32_t front, std::uint32_t back, std::uint64_t backBytes);

} // namespace vots::fit
