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

template <std::size_t N> struct UnsignedOfSize;
template <> struct UnsignedOfSize<1> { using Type = std::uint8_t; };
template <> struct UnsignedOfSize<2> { using Type = std::uint16_t; };
template <> struct UnsignedOfSize<4> { using Type = std::uint32_t; };
template <> struct UnsignedOfSize<8> { using Type = std::uint64_t; };

// Converts each sample. A non-finite float stays as it is (NaN and Inf are no data, docs/DESIGN.md §4),
// and a double beyond float range becomes an infinity: converting it would be undefined behaviour.
template <typename T> void decodeAs(const unsigned char* src, std::size_t count, bool swap, float* dst) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    for (std::size_t i = 0; i < count; ++i) {
        U bits;
        std::memcpy(&bits, src + i * sizeof(T), sizeof(T));
        if (swap) bits = byteSwapped(bits);
        const T value = std::bit_cast<T>(bits);
        if constexpr (std::is_same_v<T, double>) {
            if (std::fabs(value) > std::numeric_limits<float>::max()) {
                dst[i] = value < 0 ? -std::numeric_limits<float>::infinity()
                                   : std::numeric_limits<float>::infinity();
                continue;
            }
        }
        dst[i] = static_cast<float>(value);
    }
}

} // namespace

std::optional<ScalarType> findScalarType(const std::string& text) {
    return findNamed<ScalarType>(normaliseTypeText(text));
}

Volume gridWithoutSamples(const std::array<int, 3>& dims, const std::array<double, 3>& spacing,
                          const std::array<double, 3>& origin, const std::optional<PatientAxes>& axes,
                          ScalarType type, std::string name) {
    Volume volume;
    volume.dims = dims;
    volume.spacing = spacing;
    volume.origin = origin;
    if (axes) {
        volume.patientAxes = *axes;
        volume.orientationKnown = true;
    }
    volume.sourceType = type;
    volume.name = std::move(name);
    return volume;
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

std::vector<float> decodeSamples(const unsigned char* bytes, std::size_t count, ScalarType type,
                                 bool bigEndian) {
    std::vector<float> values(count);
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
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
        decodeAs<float>(bytes, count, swap, values.data());
        break;
    case ScalarType::Float64:
        decodeAs<double>(bytes, count, swap, values.data());
        break;
    }
    return values;
}

bool keepsCompact(ScalarType type, SampleStorage storage) {
    return storage == SampleStorage::Source && scalarTypeSize(type) <= 2;
}

namespace {

// Decodes samples whose file bytes sit at the start of `dst`'s own memory, from the last to the first:
// a float is never narrower than the sample it replaces, so each write lands on bytes already read.
template <typename T> void decodeInPlace(float* dst, std::size_t count, bool swap) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    static_assert(sizeof(T) <= sizeof(float));
    const unsigned char* src = reinterpret_cast<const unsigned char*>(dst);
    for (std::size_t i = count; i-- > 0;) {
        U bits;
        std::memcpy(&bits, src + i * sizeof(T), sizeof(T));
        if (swap) bits = byteSwapped(bits);
        const float out = static_cast<float>(std::bit_cast<T>(bits));
        std::memcpy(reinterpret_cast<unsigned char*>(dst) + i * sizeof(float), &out, sizeof(float));
    }
}

// The samples of an 8- or 16-bit file in their own type: fill(data, bytes) writes the file's bytes,
// which are then put in host byte order.
template <typename T, class Fill>
std::vector<T> compactSamples(std::size_t count, bool bigEndian, Fill& fill) {
    using U = typename UnsignedOfSize<sizeof(T)>::Type;
    std::vector<T> out(count);
    fill(reinterpret_cast<unsigned char*>(out.data()), count * sizeof(T));
    if (sizeof(T) > 1 && bigEndian != (std::endian::native == std::endian::big))
        for (T& value : out)
            value = std::bit_cast<T>(byteSwapped(std::bit_cast<U>(value)));
    return out;
}

// Volume::compact from the file's bytes (see compactSamples); false for a type it does not hold.
template <class Fill>
bool storeCompact(Volume& volume, ScalarType type, std::size_t count, bool bigEndian, Fill&& fill) {
    switch (type) {
    case ScalarType::UInt8:
        volume.compact = compactSamples<std::uint8_t>(count, bigEndian, fill);
        break;
    case ScalarType::Int8:
        volume.compact = compactSamples<std::int8_t>(count, bigEndian, fill);
        break;
    case ScalarType::UInt16:
        volume.compact = compactSamples<std::uint16_t>(count, bigEndian, fill);
        break;
    case ScalarType::Int16:
        volume.compact = compactSamples<std::int16_t>(count, bigEndian, fill);
        break;
    default: // keepsCompact holds only for the types above
        return false;
    }
    volume.values.clear();
    return true;
}

} // namespace

void readSamples(Volume& volume, std::size_t count, ScalarType type, bool bigEndian, SampleStorage storage,
                 const PayloadReader& read) {
    if (type == ScalarType::Float64) {
        std::vector<unsigned char> payload(count * sizeof(double));
        read(payload.data());
        storeSamples(volume, payload.data(), count, type, bigEndian, storage);
        return;
    }
    if (keepsCompact(type, storage) &&
        storeCompact(volume, type, count, bigEndian, [&](unsigned char* dst, std::size_t) { read(dst); }))
        return;
    std::vector<float> values(count);
    read(reinterpret_cast<unsigned char*>(values.data()));
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    switch (type) {
    case ScalarType::UInt8:
        decodeInPlace<std::uint8_t>(values.data(), count, swap);
        break;
    case ScalarType::Int8:
        decodeInPlace<std::int8_t>(values.data(), count, swap);
        break;
    case ScalarType::UInt16:
        decodeInPlace<std::uint16_t>(values.data(), count, swap);
        break;
    case ScalarType::Int16:
        decodeInPlace<std::int16_t>(values.data(), count, swap);
        break;
    case ScalarType::UInt32:
        decodeInPlace<std::uint32_t>(values.data(), count, swap);
        break;
    case ScalarType::Int32:
        decodeInPlace<std::int32_t>(values.data(), count, swap);
        break;
    case ScalarType::Float32:
        decodeInPlace<float>(values.data(), count, swap);
        break;
    case ScalarType::Float64: // read above
        break;
    }
    volume.compact = std::monostate{};
    volume.values = std::move(values);
}

void storeSamples(Volume& volume, const unsigned char* bytes, std::size_t count, ScalarType type,
                  bool bigEndian, SampleStorage storage) {
    if (!keepsCompact(type, storage)) {
        volume.values = decodeSamples(bytes, count, type, bigEndian);
        return;
    }
    storeCompact(volume, type, count, bigEndian,
                 [&](unsigned char* dst, std::size_t size) { std::memcpy(dst, bytes, size); });
}

} // namespace vots::fit::detail
