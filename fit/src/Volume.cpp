// Sample type names, the value range and content CRC of a Volume (file reading: VolumeLoad.cpp).
#include "vots/fit/Volume.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include "Crc32.h"
#include "SampleAccess.h"
#include "SampleDecode.h"

#include <algorithm>

namespace vots::fit {

std::string scalarTypeName(ScalarType type) {
    switch (type) {
    case ScalarType::UInt8:
        return "uint8";
    case ScalarType::Int8:
        return "int8";
    case ScalarType::UInt16:
        return "uint16";
    case ScalarType::Int16:
        return "int16";
    case ScalarType::UInt32:
        return "uint32";
    case ScalarType::Int32:
        return "int32";
    case ScalarType::Float32:
        return "float32";
    case ScalarType::Float64:
        return "float64";
    }
    return "unknown";
}

ScalarType parseScalarType(const std::string& text) {
    if (const auto type = detail::findScalarType(text)) return *type;
    throw InputError("unknown sample type '" + text +
                     "' (expected uint8, int8, uint16, int16, uint32, int32, float32 or float64)");
}

std::size_t Volume::heldSamples() const {
    if (!isCompact()) return values.size();
    return std::visit(
        [](const auto& held) -> std::size_t {
            if constexpr (std::is_same_v<std::decay_t<decltype(held)>, std::monostate>)
                return 0;
            else
                return held.size();
        },
        compact);
}

std::array<float, 2> Volume::valueRange() const {
    const std::size_t count = heldSamples();
    if (count == 0) return {0.0f, 0.0f};
    return visitSamples(*this, [count](const auto* samples) -> std::array<float, 2> {
        // A plain min/max the compiler vectorises; std::minmax_element tracks positions and does not (a
        // fit calls this more than once, on its serial path). NaN samples are skipped alike.
        float lo = sampleAsFloat(samples[0]), hi = lo;
        for (std::size_t i = 0; i < count; ++i) {
            const float v = sampleAsFloat(samples[i]);
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        return {lo, hi};
    });
}

std::uint32_t Volume::contentCrc() const {
    std::uint32_t crc = crc32Update(0, dims.data(), sizeof dims);
    crc = crc32Update(crc, spacing.data(), sizeof spacing);
    crc = crc32Update(crc, origin.data(), sizeof origin);
    if (!isCompact()) return crc32Update(crc, values.data(), values.size() * sizeof(float));
    // Over the samples as floats, a block at a time, so a compact volume has its float twin's CRC
    // without a float copy of itself.
    const std::size_t count = heldSamples();
    return visitSamples(*this, [&](const auto* samples) {
        constexpr std::size_t BLOCK = 4096;
        float block[BLOCK];
        for (std::size_t first = 0; first < count; first += BLOCK) {
            const std::size_t n = std::min(BLOCK, count - first);
            for (std::size_t i = 0; i < n; ++i)
                block[i] = sampleAsFloat(samples[first + i]);
            crc = crc32Update(crc, block, n * sizeof(float));
        }
        return crc;
    });
}

} // namespace vots::fit
