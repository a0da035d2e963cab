// Private: sample type sizes and spellings, size limits, and bytes -> float decoding for every reader.
#include "SampleDecode.h"

#include "InputFile.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

namespace vots::fit::detail {

std::size_t scalarTypeSize(ScalarType type) {
    switch (type) {
    case ScalarType::UInt8:
    case ScalarType::Int8:
        return 1;
    case ScalarType::UInt16:
    case ScalarType::Int16:
        return 2;
    case ScalarType::UInt32:
    case ScalarType::Int32:
    case ScalarType::Float32:
        return 4;
    case ScalarType::Float64:
        return 8;
    }
    return 1;
}

namespace {

// Lower case, runs of white space collapsed to one blank, so "unsigned  Char" matches "unsigned char".
std::string normaliseTypeText(const std::string& text) {
    std::string out;
    for (const char c : text) {
        if (std::isspace(static_cast<unsigned char>(c))) {
            if (!out.empty() && out.back() != ' ') out += ' ';
        } else {
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        }
    }
    if (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

// NRRD spellings (teem's list), C names and our own short names.
const std::pair<const char*, ScalarType> TYPE_NAMES[] = {
    {"uint8", ScalarType::UInt8},
    {"uint8_t", ScalarType::UInt8},
    {"uchar", ScalarType::UInt8},
    {"unsigned char", ScalarType::UInt8},
    {"int8", ScalarType::Int8},
    {"int8_t", ScalarType::Int8},
    {"char", ScalarType::Int8},
    {"signed char", ScalarType::Int8},
    {"uint16", ScalarType::UInt16},
    {"uint16_t", ScalarType::UInt16},
    {"ushort", ScalarType::UInt16},
    {"unsigned short", ScalarType::UInt16},
    {"unsigned short int", ScalarType::UInt16},
    {"int16", ScalarType::Int16},
    {"int16_t", ScalarType::Int16},
    {"short", ScalarType::Int16},
    {"short int", ScalarType::Int16},
    {"signed short", ScalarType::Int16},
    {"signed short int", ScalarType::Int16},
    {"uint32", ScalarType::UInt32},
    {"uint32_t", ScalarType::UInt32},
    {"uint", ScalarType::UInt32},
    {"unsigned int", ScalarType::UInt32},
    {"int32", ScalarType::Int32},
    {"int32_t", ScalarType::Int32},
    {"int", ScalarType::Int32},
    {"signed int", ScalarType::Int32},
    {"float", ScalarType::Float32},
    {"float32", ScalarType::Float32},
    {"double", ScalarType::Float64},
    {"float64", ScalarType::Float64},
};

template <std::size_t N> struct UnsignedOfSize;
template <> struct UnsignedOfSize<1> { using Type = std::uint8_t; };
template <> struct UnsignedOfSize<2> { using Type = std::uint16_t; };
template <> struct UnsignedOfSize<4> { using Type = std::uint32_t; };
template <> struct UnsignedOfSize<8> { using Type = std::uint64_t; };

// Converts each sample; returns the number of samples that are not finite floats (those become 0).
template <typename T>
std::size_t decodeAs(const unsigned char* src, std::size_t count, bool swap, float* dst) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    std::size_t bad = 0;
    for (std::size_t i = 0; i < count; ++i) {
        U bits;
        std::memcpy(&bits, src + i * sizeof(T), sizeof(T));
        if (swap) bits = byteSwapped(bits);
        const T value = std::bit_cast<T>(bits);
        if constexpr (std::is_floating_point_v<T>) {
            // A double beyond float range would be undefined behaviour to convert; count it as bad.
            const bool finite = std::isfinite(value) &&
                                std::fabs(static_cast<double>(value)) <= std::numeric_limits<float>::max();
            if (!finite) {
                ++bad;
                dst[i] = 0.0f;
                continue;
            }
        }
        dst[i] = static_cast<float>(value);
    }
    return bad;
}

} // namespace

std::optional<ScalarType> findScalarType(const std::string& text) {
    const std::string key = normaliseTypeText(text);
    for (const auto& [name, type] : TYPE_NAMES)
        if (key == name) return type;
    return std::nullopt;
}

CheckedShape checkShape(const std::string& path, const std::array<long long, 3>& dims, ScalarType type) {
    CheckedShape shape;
    std::uint64_t samples = 1;
    for (int a = 0; a < 3; ++a) {
        if (dims[a] <= 0)
            throwInputError(path, std::string("size along ") + "xyz"[a] + " is " + std::to_string(dims[a]) +
                                      " (must be positive)");
        // Each factor is checked against the cap before multiplying, so the product cannot overflow.
        if (static_cast<std::uint64_t>(dims[a]) > MAX_SAMPLES ||
            samples * static_cast<std::uint64_t>(dims[a]) > MAX_SAMPLES)
            throwInputError(path, "sizes " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
                                      " x " + std::to_string(dims[2]) + " exceed the limit of " +
                                      std::to_string(MAX_SAMPLES) + " samples");
        samples *= static_cast<std::uint64_t>(dims[a]);
        shape.dims[a] = static_cast<int>(dims[a]);
    }
    const std::uint64_t bytes = samples * scalarTypeSize(type);
    if (bytes > MAX_PAYLOAD_BYTES)
        throwInputError(path, "payload of " + std::to_string(bytes) + " bytes exceeds the limit of " +
                                  std::to_string(MAX_PAYLOAD_BYTES));
    shape.samples = static_cast<std::size_t>(samples);
    shape.bytes = static_cast<std::size_t>(bytes);
    return shape;
}

std::vector<float> decodeSamples(const std::string& path, const unsigned char* bytes, std::size_t count,
                                 ScalarType type, bool bigEndian) {
    std::vector<float> values(count);
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    std::size_t bad = 0;
    switch (type) {
    case ScalarType::UInt8:
        decodeAs<std::uint8_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::Int8:
        decodeAs<std::int8_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::UInt16:
        decodeAs<std::uint16_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::Int16:
        decodeAs<std::int16_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::UInt32:
        decodeAs<std::uint32_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::Int32:
        decodeAs<std::int32_t>(bytes, count, swap, values.data());
        break;
    case ScalarType::Float32:
        bad = decodeAs<float>(bytes, count, swap, values.data());
        break;
    case ScalarType::Float64:
        bad = decodeAs<double>(bytes, count, swap, values.data());
        break;
    }
    if (bad > 0)
        throwInputError(path, std::to_string(bad) + " of " + std::to_string(count) +
                                  " samples are not finite (NaN, Inf or beyond float range)");
    return values;
}

} // namespace vots::fit::detail
