// A box of grid cells every ray of the Vot walk is cut to: under mpirun, the z slab of cells one rank holds.
#pragma once

#include <algorithm>
#include <array>
#include <optional>

namespace vots::render {

/// Cells [lo, hi) per axis (x, y, z) of a grid of `dims - 1` cells. A ray counts only inside it, exactly:
/// outside nothing is taken, not even background, and the mean divides by the length inside it.
struct CellDomain {
    std::array<int, 3> lo{0, 0, 0};
    std::array<int, 3> hi{0, 0, 0};
    bool empty() const { return lo[0] >= hi[0] || lo[1] >= hi[1] || lo[2] >= hi[2]; }
    friend bool operator==(const CellDomain&, const CellDomain&) = default;
};

/// The part of `domain` inside a grid of `cells` cells per axis; nullopt: the whole grid.
inline CellDomain domainInGrid(const std::optional<CellDomain>& domain, const std::array<int, 3>& cells) {
    CellDomain whole{{0, 0, 0}, cells};
    if (!domain) return whole;
    for (int a = 0; a < 3; ++a) {
        whole.lo[a] = std::clamp(domain->lo[a], 0, cells[a]);
        whole.hi[a] = std::clamp(domain->hi[a], whole.lo[a], cells[a]);
    }
    return whole;
}

} // namespace vots::render
