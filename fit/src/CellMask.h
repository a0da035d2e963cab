// Which cells are background (all 8 corners below the threshold), with O(1) counts over boxes.
#pragma once

#include "vots/fit/Box.h"
#include "vots/fit/Volume.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace vots::fit {

/// Cell (i,j,k) spans grid points [i,i+1]x[j,j+1]x[k,k+1]. Keeps a 3D prefix sum of non-background
/// cells so that counts and tight bounds over any box cost O(1) per query slab.
class CellMask {
public:
    CellMask(const Volume& volume, std::optional<float> background);

    std::array<int, 3> cellDims() const { return mCells; }
    bool isBackground(int i, int j, int k) const { return mBackground[index(i, j, k)] != 0; }
    /// Non-background cells inside the closed point box (cells [lo, hi-1]).
    std::int64_t countForeground(const Box& box) const;
    std::int64_t totalForeground() const { return countForeground(Box{{0, 0, 0}, mPointDims}); }
    std::int64_t totalCells() const { return std::int64_t{mCells[0]} * mCells[1] * mCells[2]; }
    /// Smallest box (in points) inside `box` that contains all its non-background cells.
    std::optional<Box> tightBox(const Box& box) const;

private:
    std::size_t index(int i, int j, int k) const {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(mCells[0]) *
                   (static_cast<std::size_t>(j) +
                    static_cast<std::size_t>(mCells[1]) * static_cast<std::size_t>(k));
    }
    std::int64_t prefix(int i, int j, int k) const; // count over cells [0,i) x [0,j) x [0,k)
    std::int64_t countCells(const std::array<int, 3>& lo, const std::array<int, 3>& hiExclusive) const;

    std::array<int, 3> mCells{0, 0, 0};
    std::array<int, 3> mPointDims{0, 0, 0}; // hi corner of the whole grid, as a point box
    std::vector<std::uint8_t> mBackground;
    std::vector<std::uint32_t> mPrefix; // (cx+1)(cy+1)(cz+1)
};

} // namespace vots::fit
