// Normalising and naming grid directions in patient space (see PatientAxes.h).
#include "vots/fit/PatientAxes.h"

#include <cmath>

namespace vots::fit {

namespace {

// Header matrices are printed with a few digits (NIfTI stores float32): a direction within this of an
// axis is that axis.
constexpr double ALIGNED_TOLERANCE = 1e-6;

double determinant(const PatientAxes& m) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

} // namespace

std::optional<PatientAxes> normalizedPatientAxes(const PatientAxes& directions) {
    PatientAxes unit{};
    for (int a = 0; a < 3; ++a) {
        double squares = 0.0;
        for (const double c : directions[a]) {
            if (!std::isfinite(c)) return std::nullopt;
            squares += c * c;
        }
        const double length = std::sqrt(squares);
        if (!(length > 0.0) || !std::isfinite(length)) return std::nullopt;
        for (int c = 0; c < 3; ++c)
            unit[a][c] = directions[a][c] / length;
    }
    // Unit vectors spanning a parallelepiped of volume below this are treated as degenerate.
    if (std::fabs(determinant(unit)) < 1e-3) return std::nullopt;
    // Snap float noise (0.99999994 from a float32 header) so an axis-aligned grid maps exactly.
    for (auto& axis : unit) {
        const std::string name = patientDirectionName(axis);
        if (name.empty()) continue;
        const int component = (name == "L" || name == "R") ? 0 : (name == "P" || name == "A") ? 1 : 2;
        const bool positive = name == "L" || name == "P" || name == "S";
        axis = {0.0, 0.0, 0.0};
        axis[static_cast<std::size_t>(component)] = positive ? 1.0 : -1.0;
    }
    return unit;
}

std::string patientDirectionName(const std::array<double, 3>& axis) {
    static constexpr const char* POSITIVE[3] = {"L", "P", "S"};
    static constexpr const char* NEGATIVE[3] = {"R", "A", "I"};
    for (int c = 0; c < 3; ++c) {
        bool others = true;
        for (int o = 0; o < 3; ++o)
            if (o != c && std::fabs(axis[o]) > ALIGNED_TOLERANCE) others = false;
        if (!others) continue;
        if (std::fabs(axis[c] - 1.0) <= ALIGNED_TOLERANCE) return POSITIVE[c];
        if (std::fabs(axis[c] + 1.0) <= ALIGNED_TOLERANCE) return NEGATIVE[c];
    }
    return "";
}

void rasToLps(PatientAxes& axes, std::array<double, 3>& origin) {
    auto flip = [](double& v) { v = v == 0.0 ? 0.0 : -v; };
    for (auto& axis : axes)
        for (int c = 0; c < 2; ++c)
            flip(axis[c]);
    for (int c = 0; c < 2; ++c)
        flip(origin[c]);
}

bool isAxisAligned(const PatientAxes& axes) {
    for (const auto& axis : axes)
        if (patientDirectionName(axis).empty()) return false;
    return true;
}

} // namespace vots::fit
