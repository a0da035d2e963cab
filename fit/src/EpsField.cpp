// eps(Q) for a focus sphere with a linear ramp to the context eps (docs/DESIGN.md §4).
#include "vots/fit/EpsField.h"

#include <algorithm>
#include <cmath>

namespace vots::fit {

EpsField::EpsField(float epsContext, std::optional<FocusRegion> focus)
    : mContext(epsContext), mFocus(focus) {}

float EpsField::epsAtDistance(double distance) const {
    // distance is measured from the sphere surface outward; the ramp is one radius wide.
    if (distance <= 0.0) return mFocus->epsFocus;
    const double ramp = std::max(mFocus->radius, 1.0);
    if (distance >= ramp) return mContext;
    const double t = distance / ramp;
    return static_cast<float>(mFocus->epsFocus + t * (static_cast<double>(mContext) - mFocus->epsFocus));
}

float EpsField::at(double x, double y, double z) const {
    if (!mFocus) return mContext;
    const auto& c = mFocus->centerIndex;
    const double r = std::sqrt((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) + (z - c[2]) * (z - c[2]));
    return epsAtDistance(r - mFocus->radius);
}

float EpsField::minOverBox(const Box& box) const {
    if (!mFocus) return mContext;
    // eps grows with distance from the centre, so its minimum is at the box point nearest the centre.
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double c = mFocus->centerIndex[a];
        const double nearest = std::clamp(c, static_cast<double>(box.lo[a]), static_cast<double>(box.hi[a]));
        d2 += (nearest - c) * (nearest - c);
    }
    return std::min(epsAtDistance(std::sqrt(d2) - mFocus->radius), mContext);
}

float EpsField::maxOverBox(const Box& box) const {
    if (!mFocus) return mContext;
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double c = mFocus->centerIndex[a];
        const double farthest = std::max(std::abs(box.lo[a] - c), std::abs(box.hi[a] - c));
        d2 += farthest * farthest;
    }
    return std::max(epsAtDistance(std::sqrt(d2) - mFocus->radius), mFocus->epsFocus);
}

} // namespace vots::fit
