// Which cells are background (all 8 corners below the threshold, or one NaN/Inf), with fast box counts.
#pragma once

#include "vots/fit/Box.h"
#include "vots/fit/Volume.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace vots::fit {

/// Cell (i,j,k) spans grid points [i,i+1]x[j,j+1]x[k,k+1]. One bit per cell, packed in words of
/// 4x4x4 cells (one 64-bit word each), and a 3D prefix sum of foreground cells per word: a count over
/// a box is O(1) for the words inside it plus one masked popcount per word its faces cut. A prefix sum
/// per cell would cost 4 bytes a cell, as much as the float samples (docs/DESIGN.md §4 "Background").
class CellMask {
public:
    /// noDataValue: what a cell with a non-finite corner counts as in backgroundValueSum (FitOptions).
    CellMask(const Volume& volume, std::optional<float> background, std::optional<float> noDataValue = {});

    std::array<int, 3> cellDims() const { return mCells; }
    bool isBackground(int i, int j, int k) const {
        return (mWords[wordIndex(i >> 2, j >> 2, k >> 2)] >> bitInWord(i, j, k) & 1u) == 0;
    }
    /// Non-background cells inside the closed point box (cells [lo, hi-1]).
    std::int64_t countForeground(const Box& box) const;
    std::int64_t totalForeground() const { return countForeground(Box{{0, 0, 0}, mCells}); }
    std::int64_t totalCells() const { return std::int64_t{mCells[0]} * mCells[1] * mCells[2]; }
    std::int64_t totalBackground() const { return totalCells() - totalForeground(); }
    /// Over the background cells, the sum of each one's mean corner value: the integral of the trilinear
    /// field over them, in cells (VotSpace::backgroundFill is it divided by totalBackground()).
    double backgroundValueSum() const { return mBackgroundValueSum; }
    /// Smallest box (in points) inside `box` that contains all its non-background cells.
    std::optional<Box> tightBox(const Box& box) const;

    static constexpr int WORD_CELLS = 4; // per axis: 4^3 = 64 cells, one word
    std::size_t memoryBytes() const {
        return sizeof(*this) + mWords.capacity() * sizeof(std::uint64_t) +
               mWordPrefix.capacity() * sizeof(std::uint32_t);
    }

private:
    std::size_t wordIndex(int bx, int by, int bz) const {
        return static_cast<std::size_t>(bx) +
               static_cast<std::size_t>(mWordDims[0]) *
                   (static_cast<std::size_t>(by) +
                    static_cast<std::size_t>(mWordDims[1]) * static_cast<std::size_t>(bz));
    }
    static unsigned bitInWord(int i, int j, int k) {
        return static_cast<unsigned>((i & 3) | (j & 3) << 2 | (k & 3) << 4);
    }
    std::int64_t wordPrefix(int bx, int by, int bz) const; // foreground in words [0,bx) x [0,by) x [0,bz)
    std::int64_t countCells(const std::array<int, 3>& lo, const std::array<int, 3>& hiExclusive) const;

    std::array<int, 3> mCells{0, 0, 0};
    std::array<int, 3> mWordDims{0, 0, 0};
    std::vector<std::uint64_t> mWords;      // bit (i&3) + 4 (j&3) + 16 (k&3) set: foreground cell
    std::vector<std::uint32_t> mWordPrefix; // (bx+1)(by+1)(bz+1)
    double mBackgroundValueSum = 0.0;
};

} // namespace vots::fit
