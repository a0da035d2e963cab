// Sample type names, the value range and content CRC of a Volume (file reading: VolumeLoad.cpp).
#include "vots/fit/Volume.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include "Crc32.h"
#include "SampleAccess.h"
#include "SampleDecode.h"
#include "SampleRange.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace vots::fit {

ScalarType parseScalarType(const std::string& text) {
    if (const auto type = detail::findScalarType(text)) return *type;
    throw InputError("unknown sample type '" + text + "' (known: " + knownNames<ScalarType>() + ")");
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

std::array<float, 2> finiteRange(const Volume& volume, std::size_t begin, std::size_t end) {
    return visitSamples(volume, [begin, end](const auto* samples) -> std::array<float, 2> {
        // A plain min/max the compiler vectorises; std::minmax_element tracks positions and does not (a
        // fit calls this more than once, on its serial path). NaN and Inf samples are no data: skipped.
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (std::size_t i = begin; i < end; ++i) {
            const float v = sampleAsFloat(samples[i]);
            const bool finite = std::fabs(v) <= std::numeric_limits<float>::max();
            lo = finite ? std::min(lo, v) : lo;
            hi = finite ? std::max(hi, v) : hi;
        }
        return {lo, hi};
    });
}

std::array<float, 2> usableRange(std::array<float, 2> range) {
    if (range[0] > range[1]) return {0.0f, 0.0f}; // no finite sample
    return range;
}

std::array<float, 2> Volume::valueRange() const {
    return usableRange(finiteRange(*this, 0, heldSamples()));
}

std::size_t Volume::nonFiniteCount() const {
    if (isCompact()) return 0; // integers are always finite
    return static_cast<std::size_t>(std::count_if(values.begin(), values.end(), [](float v) {
        return !(std::fabs(v) <= std::numeric_limits<float>::max());
    }));
}

namespace {

/// `crc` extended by held samples [begin, end) as floats. A compact volume goes a block at a time, so it
/// has its float twin's CRC without a float copy of itself.
std::uint32_t samplesCrc(const Volume& volume, std::uint32_t crc, std::size_t begin, std::size_t end) {
    if (!volume.isCompact())
        return crc32Update(crc, volume.values.data() + begin, (end - begin) * sizeof(float));
    return visitSamples(volume, [&](const auto* samples) {
        constexpr std::size_t BLOCK = 4096;
        float block[BLOCK];
        for (std::size_t at = begin; at < end; at += BLOCK) {
            const std::size_t n = std::min(BLOCK, end - at);
            for (std::size_t i = 0; i < n; ++i)
                block[i] = sampleAsFloat(samples[at + i]);
            crc = crc32Update(crc, block, n * sizeof(float));
        }
        return crc;
    });
}

} // namespace

std::uint32_t Volume::gridCrc() const {
    std::uint32_t crc = crc32Update(0, dims.data(), sizeof dims);
    crc = crc32Update(crc, spacing.data(), sizeof spacing);
    return crc32Update(crc, origin.data(), sizeof origin);
}

std::uint32_t Volume::planesCrc(int first, int count) const {
    const std::size_t plane = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
    if (first < 0 || count < 0 || static_cast<long long>(first) + count > dims[2])
        throw InputError("planes outside the volume's grid");
    const std::size_t begin = plane * static_cast<std::size_t>(first);
    const std::size_t end = begin + plane * static_cast<std::size_t>(count);
    if (end > heldSamples()) throw InputError("planes outside the samples held");
    return samplesCrc(*this, 0, begin, end);
}

std::uint32_t Volume::contentCrc() const {
    // Every held sample, whatever the dims say: a volume that does not match its grid still gets a key.
    return samplesCrc(*this, gridCrc(), 0, heldSamples());
}

std::uint32_t combineCrc(std::uint32_t front, std::uint32_t back, std::uint64_t backBytes) {
    return static_cast<std::uint32_t>(crc32_combine(front, back, static_cast<z_off_t>(backBytes)));
}

} // namespace vots::fit
