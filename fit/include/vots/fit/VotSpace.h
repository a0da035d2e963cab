// A set of Vots covering a volume plus the grid it came from (docs/DESIGN.md §8 header fields).
#pragma once

#include "vots/fit/Vot.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit {

struct VotSpace {
    std::array<int, 3> dims{0, 0, 0};             // grid points along x, y, z of the source volume
    std::array<double, 3> origin{0.0, 0.0, 0.0};  // world position of grid point (0,0,0)
    std::array<double, 3> spacing{1.0, 1.0, 1.0}; // world distance between grid points
    /// The source volume's grid directions in patient space (Volume::patientAxes). Not in the binary
    /// header: a file keeps them in its meta block, which meta::decodeVotSpace (vots/meta) restores.
    std::array<std::array<double, 3>, 3> patientAxes{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    bool orientationKnown = false;
    int degree = 3;         // highest degree of any nonzero stored coefficient
    float eps = 0.f;        // nominal (context) error bound, data units
    float background = 0.f; // cells with all corners below it are omitted
    /// What the omitted cells stand for in the min and the mean of a ray: the mean of the trilinear field
    /// over them (the fit's backgroundValueSum / backgroundCells). Absent when no cell was omitted, and
    /// in files written before it (a file keeps it in its meta block, like patientAxes): those count
    /// omitted cells as `background`.
    std::optional<float> backgroundFill;
    bool epsVaries = false; // flag bit 0: eps varies in space (focus region)
    std::vector<Vot> vots;
    std::string metaJson = "{}"; // UTF-8 JSON block (source, parameters, timings)

    /// The value omitted cells count as in the min and the mean: backgroundFill, else background.
    float omittedCellValue() const { return backgroundFill.value_or(background); }

    static constexpr std::uint32_t FLAG_EPS_VARIES = 1u;
};

/// The largest error bound stored in the Vots (0 for none).
inline double maxStoredError(const VotSpace& space) {
    double maxError = 0.0;
    for (const Vot& v : space.vots)
        maxError = std::max(maxError, double{v.err});
    return maxError;
}

} // namespace vots::fit
