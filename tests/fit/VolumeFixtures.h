// Test-only writers for small NRRD, NIfTI-1, MetaImage and raw files with known samples; no reading here.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>
#include <zlib.h>

namespace vots::test {

using fit::ScalarType;

/// Grid of the written fixtures: deliberately not a cube, so swapped axes show.
inline constexpr std::array<int, 3> FIXTURE_DIMS{5, 4, 3};
inline constexpr int FIXTURE_SAMPLES = 5 * 4 * 3;

/// Deterministic samples for `type`, including the type's extremes where float holds them exactly.
inline std::vector<double> fixtureValues(ScalarType type) {
    std::vector<double> values(FIXTURE_SAMPLES);
    for (int i = 0; i < FIXTURE_SAMPLES; ++i) {
        switch (type) {
        case ScalarType::UInt8:
            values[i] = (i * 37) % 256;
            break;
        case ScalarType::Int8:
            values[i] = (i * 37) % 256 - 128;
            break;
        case ScalarType::UInt16:
            values[i] = (i * 1237) % 65536;
            break;
        case ScalarType::Int16:
            values[i] = (i * 1237) % 65536 - 32768;
            break;
        case ScalarType::UInt32:
            values[i] = (i * 104729) % 16777216;
            break;
        case ScalarType::Int32:
            values[i] = (i * 104729) % 16777216 - 8388608;
            break;
        case ScalarType::Float32:
            values[i] = (i - 30) * 0.375;
            break;
        case ScalarType::Float64:
            values[i] = (i - 30) * 1.0e20 + 0.5;
            break;
        }
    }
    switch (type) { // extremes that are exact in float
    case ScalarType::UInt8:
        values[1] = 255;
        break;
    case ScalarType::Int8:
        values[1] = -128, values[2] = 127;
        break;
    case ScalarType::UInt16:
        values[1] = 65535;
        break;
    case ScalarType::Int16:
        values[1] = -32768, values[2] = 32767;
        break;
    case ScalarType::UInt32:
        values[1] = 4294967040.0;
        break;
    case ScalarType::Int32:
        values[1] = -2147483648.0;
        break;
    case ScalarType::Float32:
        values[1] = -1.0e-30;
        break;
    case ScalarType::Float64:
        values[1] = 3.0e38;
        break;
    }
    return values;
}

template <typename T> std::string encodeAs(const std::vector<double>& values, bool bigEndian) {
    std::string out;
    for (const double v : values) {
        unsigned char bytes[sizeof(T)];
        const T typed = static_cast<T>(v);
        std::memcpy(bytes, &typed, sizeof(T));
        if (bigEndian != (std::endian::native == std::endian::big))
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
                std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
        out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
    }
    return out;
}

/// The samples as the file stores them.
inline std::string encode(const std::vector<double>& values, ScalarType type, bool bigEndian) {
    switch (type) {
    case ScalarType::UInt8:
        return encodeAs<std::uint8_t>(values, bigEndian);
    case ScalarType::Int8:
        return encodeAs<std::int8_t>(values, bigEndian);
    case ScalarType::UInt16:
        return encodeAs<std::uint16_t>(values, bigEndian);
    case ScalarType::Int16:
        return encodeAs<std::int16_t>(values, bigEndian);
    case ScalarType::UInt32:
        return encodeAs<std::uint32_t>(values, bigEndian);
    case ScalarType::Int32:
        return encodeAs<std::int32_t>(values, bigEndian);
    case ScalarType::Float32:
        return encodeAs<float>(values, bigEndian);
    case ScalarType::Float64:
        return encodeAs<double>(values, bigEndian);
    }
    return {};
}

/// Appends one gzip member holding `bytes` to `path` (creating it), through zlib's gzopen/gzwrite.
inline void appendGzip(const std::string& path, const std::string& bytes) {
    gzFile file = gzopen(path.c_str(), "ab");
    if (file == nullptr) throw std::runtime_error("gzopen failed for " + path);
    const int written = bytes.empty() ? 0 : gzwrite(file, bytes.data(), static_cast<unsigned>(bytes.size()));
    if (gzclose(file) != Z_OK || written != static_cast<int>(bytes.size()))
        throw std::runtime_error("gzwrite failed for " + path);
}

/// A zlib stream (as MetaImage's CompressedData holds), through compress2.
inline std::string zlibBytes(const std::string& bytes) {
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string out(size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(bytes.data()),
                  static_cast<uLong>(bytes.size()), 6) != Z_OK)
        throw std::runtime_error("compress2 failed");
    out.resize(size);
    return out;
}

/// The fields of a NIfTI-1 header that the tests vary.
struct NiftiSpec {
    std::array<short, 8> dim{3, FIXTURE_DIMS[0], FIXTURE_DIMS[1], FIXTURE_DIMS[2], 1, 1, 1, 1};
    short datatype = 4;
    short bitpix = 16;
    std::array<float, 3> pixdim{0.5f, 1.25f, 3.0f};
    float voxOffset = 352.0f;
    float sclSlope = 0.0f;
    float sclInter = 0.0f;
    short qformCode = 0;
    short sformCode = 0;
    std::array<float, 3> qoffset{0.0f, 0.0f, 0.0f};
    std::array<float, 3> srowOffset{0.0f, 0.0f, 0.0f};
    std::array<std::array<float, 3>, 3> srow{};     // srow_x, srow_y, srow_z without their offsets (RAS)
    std::array<float, 3> quatern{0.0f, 0.0f, 0.0f}; // quatern_b, c, d
    float qfac = 1.0f;                              // pixdim[0]
    bool bigEndian = false;
    std::string magic{"n+1\0", 4};
};

/// 348 header bytes plus the 4-byte empty extension block, so data starts at 352.
inline std::string niftiHeader(const NiftiSpec& spec) {
    std::string h(352, '\0');
    const auto put = [&](std::size_t offset, auto value) {
        const std::string bytes = encodeAs<decltype(value)>({static_cast<double>(value)}, spec.bigEndian);
        h.replace(offset, bytes.size(), bytes);
    };
    put(0, std::int32_t{348});
    for (std::size_t i = 0; i < 8; ++i)
        put(40 + 2 * i, static_cast<std::int16_t>(spec.dim[i]));
    put(70, static_cast<std::int16_t>(spec.datatype));
    put(72, static_cast<std::int16_t>(spec.bitpix));
    put(76, spec.qfac);
    for (std::size_t i = 0; i < 3; ++i)
        put(80 + 4 * i, spec.pixdim[i]);
    put(108, spec.voxOffset);
    put(112, spec.sclSlope);
    put(116, spec.sclInter);
    put(252, static_cast<std::int16_t>(spec.qformCode));
    put(254, static_cast<std::int16_t>(spec.sformCode));
    for (std::size_t i = 0; i < 3; ++i)
        put(268 + 4 * i, spec.qoffset[i]);
    for (std::size_t i = 0; i < 3; ++i)
        put(292 + 16 * i, spec.srowOffset[i]);
    for (std::size_t row = 0; row < 3; ++row)
        for (std::size_t a = 0; a < 3; ++a)
            put(280 + 16 * row + 4 * a, spec.srow[row][a]);
    for (std::size_t i = 0; i < 3; ++i)
        put(256 + 4 * i, spec.quatern[i]);
    h.replace(344, 4, spec.magic);
    return h;
}

/// A detached-or-attached NRRD header for the fixture grid; `extra` lines end in '\n'.
inline std::string nrrdHeader(const std::string& type, const std::string& encoding,
                              const std::string& extra) {
    return "NRRD0004\n# written by a Vots test\ntype: " + type +
           "\ndimension: 3\nsizes: " + std::to_string(FIXTURE_DIMS[0]) + " " +
           std::to_string(FIXTURE_DIMS[1]) + " " + std::to_string(FIXTURE_DIMS[2]) +
           "\nencoding: " + encoding + "\n" + extra;
}

} // namespace vots::test
