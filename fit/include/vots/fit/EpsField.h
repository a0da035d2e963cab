// The error bound over space: a constant, or a focus sphere with its own eps (docs/DESIGN.md §4).
#pragma once

#include "vots/fit/Box.h"

#include <array>
#include <optional>

namespace vots::fit {

/// A sphere in grid index space where the user wants a tighter bound.
struct FocusRegion {
    std::array<double, 3> centerIndex{0.0, 0.0, 0.0}; // grid index space
    double radius = 0.0;                              // grid index units
    float epsFocus = 0.f;                             // bound inside the sphere (may be 0)
};

/// eps(Q): epsFocus inside the focus sphere, rising linearly with distance outside it and reaching
/// epsContext one radius beyond the surface (a ramp as wide as the sphere), epsContext elsewhere.
class EpsField {
public:
    explicit EpsField(float epsContext, std::optional<FocusRegion> focus = std::nullopt);

    float at(double x, double y, double z) const;
    /// Smallest and largest eps over the closed box (exact for the sphere-plus-ramp field).
    float minOverBox(const Box& box) const;
    float maxOverBox(const Box& box) const;
    bool varies() const { return mFocus.has_value(); }
    float context() const { return mContext; }
    const std::optional<FocusRegion>& focus() const { return mFocus; }

private:
    float epsAtDistance(double distance) const;
    float mContext;
    std::optional<FocusRegion> mFocus;
};

} // namespace vots::fit
