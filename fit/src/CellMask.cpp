// Background classification of cells and word-level counting (docs/DESIGN.md §4 "Background").
#include "CellMask.h"

#include "SampleAccess.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

namespace vots::fit {
namespace {

constexpr int B = CellMask::WORD_CELLS;

// Bits of a mask word whose coordinate along `axis` lies in [first, end) (0 <= first < end <= 4).
std::uint64_t axisMask(int axis, int first, int end) {
    std::uint64_t mask = 0;
    for (unsigned bit = 0; bit < 64; ++bit) {
        const int c = static_cast<int>(bit >> (2 * axis) & 3u);
        if (c >= first && c < end) mask |= std::uint64_t{1} << bit;
    }
    return mask;
}

struct AxisMasks {
    std::uint64_t table[3][B + 1][B + 1]{};
    AxisMasks() {
        for (int a = 0; a < 3; ++a)
            for (int s = 0; s <= B; ++s)
                for (int e = s; e <= B; ++e)
                    table[a][s][e] = axisMask(a, s, e);
    }
};
const AxisMasks AXIS_MASKS;

// A sample that is NaN or Inf: no data (docs/DESIGN.md §4 "Non-finite samples"). Integers never are.
template <typename T> bool isNoData(T value) {
    if constexpr (std::is_floating_point_v<T>)
        return !(std::fabs(value) <= std::numeric_limits<T>::max());
    else
        return false;
}

// The sum of the 8 corner samples of every background cell (isBackground[i] != 0) in the row of cells
// (j, k), in double: a volume's background can hold billions of samples. A cell with a non-finite corner
// counts as `noDataValue` at all 8: its finite corners may be bright data next to the no-data region, and
// the fill must stay below the threshold as a cell below it would (docs/DESIGN.md §4).
template <typename T>
double backgroundCornerSum(const T* values, std::size_t nx, std::size_t nxy, int j, int k,
                           const std::vector<std::uint8_t>& isBackground, float noDataValue) {
    const T* p00 = values + static_cast<std::size_t>(k) * nxy + static_cast<std::size_t>(j) * nx;
    const T* p10 = p00 + nx;
    const T* p01 = p00 + nxy;
    const T* p11 = p01 + nx;
    double sum = 0.0;
    for (std::size_t i = 0; i < isBackground.size(); ++i) {
        if (!isBackground[i]) continue;
        double corners = 0.0;
        bool noData = false;
        for (const T* p : {p00, p10, p01, p11}) {
            corners += double{sampleAsFloat(p[i])} + double{sampleAsFloat(p[i + 1])};
            noData = noData || isNoData(p[i]) || isNoData(p[i + 1]);
        }
        sum += noData ? 8.0 * noDataValue : corners;
    }
    return sum;
}

// Per-sample flags of markForeground: below the threshold, and no data.
constexpr std::uint8_t LOW = 1, NO_DATA = 2;

// Sets the foreground bits from the samples: a cell is background when all 8 corners are below tau or
// any corner is no data (NaN, Inf). Slice by slice over contiguous bytes, which the compiler vectorises;
// two slices of flags are all the scratch it needs (a flag per sample would be as large as the samples).
// Returns the sum over background cells of the mean of each one's 8 corners
// (CellMask::backgroundValueSum), a non-finite corner counting as `noDataValue`.
template <typename T>
double markForeground(const T* values, const std::array<int, 3>& dims, std::optional<float> background,
                      const std::array<int, 3>& cells, float noDataValue, const auto& setRow) {
    const std::size_t nx = static_cast<std::size_t>(dims[0]);
    const std::size_t nxy = nx * static_cast<std::size_t>(dims[1]);
    std::vector<std::uint8_t> row(static_cast<std::size_t>(cells[0]), 0);
    if (!background && !std::is_floating_point_v<T>) {
        for (int k = 0; k < cells[2]; ++k)
            for (int j = 0; j < cells[1]; ++j)
                setRow(j, k, row.data()); // all zero: no cell is background
        return 0.0;
    }
    // Without a threshold nothing is low (no sample is below -inf), but no-data cells are still left out.
    const float tau = background ? *background : -std::numeric_limits<float>::infinity();
    std::vector<std::uint8_t> flagsBelow(nxy), flagsAbove(nxy);
    auto markFlags = [&](int z, std::vector<std::uint8_t>& flags) {
        const T* slice = values + static_cast<std::size_t>(z) * nxy;
        for (std::size_t n = 0; n < nxy; ++n) {
            const T v = slice[n];
            flags[n] =
                static_cast<std::uint8_t>((sampleAsFloat(v) < tau ? LOW : 0) | (isNoData(v) ? NO_DATA : 0));
        }
    };
    double cornerSum = 0.0; // over background cells, of their 8 corners
    markFlags(0, flagsBelow);
    for (int k = 0; k < cells[2]; ++k) {
        markFlags(k + 1, flagsAbove);
        for (int j = 0; j < cells[1]; ++j) {
            const std::uint8_t* r00 = flagsBelow.data() + static_cast<std::size_t>(j) * nx;
            const std::uint8_t* r10 = r00 + nx;
            const std::uint8_t* r01 = flagsAbove.data() + static_cast<std::size_t>(j) * nx;
            const std::uint8_t* r11 = r01 + nx;
            bool anyBackground = false;
            for (int i = 0; i < cells[0]; ++i) {
                const std::uint8_t all =
                    r00[i] & r00[i + 1] & r10[i] & r10[i + 1] & r01[i] & r01[i + 1] & r11[i] & r11[i + 1];
                const std::uint8_t any =
                    r00[i] | r00[i + 1] | r10[i] | r10[i + 1] | r01[i] | r01[i + 1] | r11[i] | r11[i + 1];
                const std::uint8_t omitted = static_cast<std::uint8_t>((all & LOW) | (any & NO_DATA) >> 1);
                row[static_cast<std::size_t>(i)] = omitted;
                anyBackground |= omitted != 0;
            }
            setRow(j, k, row.data());
            // Most rows of a volume cut through an object hold no background; those cost nothing more.
            if (anyBackground) cornerSum += backgroundCornerSum(values, nx, nxy, j, k, row, noDataValue);
        }
        flagsBelow.swap(flagsAbove);
    }
    return cornerSum / 8.0;
}

} // namespace

CellMask::CellMask(const Volume& volume, std::optional<float> background, std::optional<float> noDataValue) {
    for (int a = 0; a < 3; ++a) {
        mCells[a] = std::max(volume.dims[a] - 1, 0);
        mWordDims[a] = (mCells[a] + B - 1) / B;
    }
    mWords.assign(static_cast<std::size_t>(mWordDims[0]) * mWordDims[1] * mWordDims[2], 0);
    if (totalCells() > 0) {
        auto setRow = [&](int j, int k, const std::uint8_t* isBackgroundRow) {
            std::uint64_t* words = mWords.data() + wordIndex(0, j >> 2, k >> 2);
            const unsigned rowBits = static_cast<unsigned>((j & 3) << 2 | (k & 3) << 4);
            for (int i = 0; i < mCells[0]; ++i)
                words[i >> 2] |= std::uint64_t{isBackgroundRow[i] ? 0u : 1u} << (rowBits | (i & 3));
        };
        // Cells with a non-finite corner count in the fill as the lowest finite sample: no data reads as
        // the darkest data in a MinIP and the average (docs/DESIGN.md §4 "Non-finite samples").
        const float noData = noDataValue ? *noDataValue : volume.isCompact() ? 0.0f : volume.valueRange()[0];
        visitSamples(volume, [&](const auto* values) {
            mBackgroundValueSum = markForeground(values, volume.dims, background, mCells, noData, setRow);
        });
    }
    // The 3D prefix sum over words as three 1D passes (x, then y, then z), each over whole rows.
    const std::size_t px = static_cast<std::size_t>(mWordDims[0]) + 1,
                      py = static_cast<std::size_t>(mWordDims[1]) + 1,
                      pz = static_cast<std::size_t>(mWordDims[2]) + 1;
    mWordPrefix.assign(px * py * pz, 0);
    auto row = [&](std::size_t j, std::size_t k) { return mWordPrefix.data() + px * (j + py * k); };
    for (int k = 1; k <= mWordDims[2]; ++k)
        for (int j = 1; j <= mWordDims[1]; ++j) {
            std::uint32_t* out = row(static_cast<std::size_t>(j), static_cast<std::size_t>(k));
            const std::uint64_t* words = mWords.data() + wordIndex(0, j - 1, k - 1);
            for (int i = 1; i <= mWordDims[0]; ++i)
                out[i] = out[i - 1] + static_cast<std::uint32_t>(std::popcount(words[i - 1]));
        }
    for (std::size_t k = 1; k < pz; ++k)
        for (std::size_t j = 1; j < py; ++j) {
            std::uint32_t* out = row(j, k);
            const std::uint32_t* before = row(j - 1, k);
            for (std::size_t i = 0; i < px; ++i)
                out[i] += before[i];
        }
    for (std::size_t k = 1; k < pz; ++k)
        for (std::size_t j = 0; j < py; ++j) {
            std::uint32_t* out = row(j, k);
            const std::uint32_t* below = row(j, k - 1);
            for (std::size_t i = 0; i < px; ++i)
                out[i] += below[i];
        }
}

std::int64_t CellMask::wordPrefix(int bx, int by, int bz) const {
    const std::size_t px = static_cast<std::size_t>(mWordDims[0]) + 1,
                      py = static_cast<std::size_t>(mWordDims[1]) + 1;
    return mWordPrefix[static_cast<std::size_t>(bx) +
                       px * (static_cast<std::size_t>(by) + py * static_cast<std::size_t>(bz))];
}

std::int64_t CellMask::countCells(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
    if (hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2]) return 0;
    // Words the box touches [first, end) and those wholly inside it [innerFirst, innerEnd).
    std::array<int, 3> first{}, end{}, innerFirst{}, innerEnd{};
    bool hasInner = true;
    for (int a = 0; a < 3; ++a) {
        first[a] = lo[a] / B;
        end[a] = (hi[a] + B - 1) / B;
        innerFirst[a] = (lo[a] + B - 1) / B;
        innerEnd[a] = hi[a] / B;
        if (innerFirst[a] >= innerEnd[a]) hasInner = false;
    }
    std::int64_t count = 0;
    if (hasInner) {
        const auto &f = innerFirst, &e = innerEnd;
        count = wordPrefix(e[0], e[1], e[2]) - wordPrefix(f[0], e[1], e[2]) - wordPrefix(e[0], f[1], e[2]) -
                wordPrefix(e[0], e[1], f[2]) + wordPrefix(f[0], f[1], e[2]) + wordPrefix(f[0], e[1], f[2]) +
                wordPrefix(e[0], f[1], f[2]) - wordPrefix(f[0], f[1], f[2]);
    }
    // The part of a word inside the box, as bits: each axis's range within the word.
    auto range = [&](int axis, int word) {
        const int s = std::max(lo[axis] - word * B, 0), e = std::min(hi[axis] - word * B, B);
        return AXIS_MASKS.table[axis][s][e];
    };
    auto inside = [&](int axis, int word) { return word >= innerFirst[axis] && word < innerEnd[axis]; };
    for (int bz = first[2]; bz < end[2]; ++bz) {
        const std::uint64_t mz = range(2, bz);
        for (int by = first[1]; by < end[1]; ++by) {
            const std::uint64_t myz = mz & range(1, by);
            const std::uint64_t* words = mWords.data() + wordIndex(0, by, bz);
            auto add = [&](int bx) { count += std::popcount(words[bx] & myz & range(0, bx)); };
            if (hasInner && inside(2, bz) && inside(1, by)) {
                // The inner words of this row are already counted: only the cut ones at its ends.
                for (int bx = first[0]; bx < innerFirst[0]; ++bx)
                    add(bx);
                for (int bx = innerEnd[0]; bx < end[0]; ++bx)
                    add(bx);
            } else {
                for (int bx = first[0]; bx < end[0]; ++bx)
                    add(bx);
            }
        }
    }
    return count;
}

std::int64_t CellMask::countForeground(const Box& box) const {
    return countCells(box.lo, box.hi);
}

std::optional<Box> CellMask::tightBox(const Box& box) const {
    std::array<int, 3> lo = box.lo, hi = box.hi; // cells [lo, hi)
    const std::int64_t foreground = countCells(lo, hi);
    if (foreground == 0) return std::nullopt;
    if (foreground == box.cellCount()) return box; // most boxes inside an object: no slab to trim
    for (int a = 0; a < 3; ++a) {
        auto slabCount = [&](int first) {
            std::array<int, 3> slo = lo, shi = hi;
            slo[a] = first;
            shi[a] = first + 1;
            return countCells(slo, shi);
        };
        while (slabCount(lo[a]) == 0)
            ++lo[a];
        while (slabCount(hi[a] - 1) == 0)
            --hi[a];
    }
    return Box{lo, hi};
}

} // namespace vots::fit
