// Narrowing a bound to float so that it stays a bound: an upper one rounds up, a lower one down.
#pragma once

#include <cmath>

namespace vots::fit {

/// The recorded error must stay an upper bound after narrowing to float.
inline float roundUpToFloat(double value) {
    const float f = static_cast<float>(value);
    return static_cast<double>(f) < value ? std::nextafter(f, INFINITY) : f;
}

/// A lower bound stays one after narrowing to float.
inline float roundDownToFloat(double value) {
    const float f = static_cast<float>(value);
    return static_cast<double>(f) > value ? std::nextafter(f, -INFINITY) : f;
}

} // namespace vots::fit
