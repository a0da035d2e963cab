// Closed integer box [lo, hi] in grid index space; a validity region and the unit of cover.
#pragma once

#include <array>
#include <cstdint>

namespace vots::fit {

/// Closed interval box of grid points: point (i,j,k) is inside iff lo <= (i,j,k) <= hi on every axis.
/// A valid Vot box has lo < hi on every axis, so it contains at least one cell.
struct Box {
    std::array<int, 3> lo{0, 0, 0};
    std::array<int, 3> hi{0, 0, 0};

    int points(int axis) const { return hi[axis] - lo[axis] + 1; }
    int cells(int axis) const { return hi[axis] - lo[axis]; }
    std::int64_t pointCount() const { return std::int64_t{points(0)} * points(1) * points(2); }
    std::int64_t cellCount() const { return std::int64_t{cells(0)} * cells(1) * cells(2); }
    bool isValid() const { return lo[0] < hi[0] && lo[1] < hi[1] && lo[2] < hi[2]; }
    bool containsClosed(const Box& o) const {
        for (int a = 0; a < 3; ++a)
            if (o.lo[a] < lo[a] || o.hi[a] > hi[a]) return false;
        return true;
    }
    bool containsPointClosed(int x, int y, int z) const {
        return x >= lo[0] && x <= hi[0] && y >= lo[1] && y <= hi[1] && z >= lo[2] && z <= hi[2];
    }
    friend bool operator==(const Box&, const Box&) = default;
};

} // namespace vots::fit
