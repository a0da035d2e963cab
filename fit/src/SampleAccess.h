// Private: hands the fitting loops a typed pointer to a Volume's samples, float or compact.
#pragma once

#include "vots/fit/Volume.h"

#include <type_traits>
#include <variant>

namespace vots::fit {

/// Every sample is read through this: the float the loops computed with when all samples were floats,
/// so a compact volume gives the same sums, residuals and Vots bit for bit.
template <typename T> inline float sampleAsFloat(T value) {
    return static_cast<float>(value);
}

/// Calls body(const T* samples) with T the type the samples are held in (float, or a compact type).
template <typename Body> decltype(auto) visitSamples(const Volume& volume, Body&& body) {
    if (!volume.isCompact()) return body(volume.values.data());
    return std::visit(
        [&](const auto& held) -> decltype(auto) {
            if constexpr (std::is_same_v<std::decay_t<decltype(held)>, std::monostate>)
                return body(volume.values.data()); // not reached: isCompact() is false for monostate
            else
                return body(held.data());
        },
        volume.compact);
}

/// The first sample's address, whatever its type: identifies the sample storage (FitCache::bind).
inline const void* sampleData(const Volume& volume) {
    return visitSamples(volume, [](const auto* samples) { return static_cast<const void*>(samples); });
}

} // namespace vots::fit
