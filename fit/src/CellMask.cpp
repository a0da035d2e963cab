// Background classification of cells and prefix-sum counting (DESIGN §4 "Background").
#include "CellMask.h"

#include <algorithm>

namespace vots::fit {

CellMask::CellMask(const Volume& volume, std::optional<float> background) {
    for (int a = 0; a < 3; ++a) {
        mCells[a] = std::max(volume.dims[a] - 1, 0);
        mPointDims[a] = std::max(volume.dims[a] - 1, 0);
    }
    const std::size_t cellCount = static_cast<std::size_t>(totalCells());
    mBackground.assign(cellCount, 0);
    if (background) {
        const float tau = *background;
        // A point is "low" when below tau; a cell is background when all 8 corners are low.
        std::vector<std::uint8_t> low(volume.sampleCount());
        for (std::size_t n = 0; n < low.size(); ++n)
            low[n] = volume.values[n] < tau ? 1 : 0;
        for (int k = 0; k < mCells[2]; ++k)
            for (int j = 0; j < mCells[1]; ++j)
                for (int i = 0; i < mCells[0]; ++i) {
                    bool all = true;
                    for (int c = 0; c < 8 && all; ++c)
                        all = low[volume.indexOf(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] != 0;
                    mBackground[index(i, j, k)] = all ? 1 : 0;
                }
    }
    const std::size_t px = static_cast<std::size_t>(mCells[0]) + 1,
                      py = static_cast<std::size_t>(mCells[1]) + 1;
    mPrefix.assign(px * py * (static_cast<std::size_t>(mCells[2]) + 1), 0);
    auto at = [&](int i, int j, int k) -> std::uint32_t& {
        return mPrefix[static_cast<std::size_t>(i) +
                       px * (static_cast<std::size_t>(j) + py * static_cast<std::size_t>(k))];
    };
    for (int k = 1; k <= mCells[2]; ++k)
        for (int j = 1; j <= mCells[1]; ++j)
            for (int i = 1; i <= mCells[0]; ++i) {
                const std::uint32_t fg = mBackground[index(i - 1, j - 1, k - 1)] ? 0u : 1u;
                at(i, j, k) = fg + at(i - 1, j, k) + at(i, j - 1, k) + at(i, j, k - 1) - at(i - 1, j - 1, k) -
                              at(i - 1, j, k - 1) - at(i, j - 1, k - 1) + at(i - 1, j - 1, k - 1);
            }
}

std::int64_t CellMask::prefix(int i, int j, int k) const {
    const std::size_t px = static_cast<std::size_t>(mCells[0]) + 1,
                      py = static_cast<std::size_t>(mCells[1]) + 1;
    return mPrefix[static_cast<std::size_t>(i) +
                   px * (static_cast<std::size_t>(j) + py * static_cast<std::size_t>(k))];
}

std::int64_t CellMask::countCells(const std::array<int, 3>& lo, const std::array<int, 3>& hi) const {
    if (hi[0] <= lo[0] || hi[1] <= lo[1] || hi[2] <= lo[2]) return 0;
    return prefix(hi[0], hi[1], hi[2]) - prefix(lo[0], hi[1], hi[2]) - prefix(hi[0], lo[1], hi[2]) -
           prefix(hi[0], hi[1], lo[2]) + prefix(lo[0], lo[1], hi[2]) + prefix(lo[0], hi[1], lo[2]) +
           prefix(hi[0], lo[1], lo[2]) - prefix(lo[0], lo[1], lo[2]);
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
