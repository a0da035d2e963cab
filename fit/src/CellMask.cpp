// Background classification of cells and prefix-sum counting (docs/DESIGN.md §4 "Background").
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
    if (background && cellCount > 0) {
        const float tau = *background;
        // A point is "low" when below tau; a cell is background when all 8 corners are low. Row by row
        // over contiguous bytes, which the compiler vectorises, rather than an index lookup per corner:
        // the mask is built on the fit's serial path.
        std::vector<std::uint8_t> low(volume.sampleCount());
        for (std::size_t n = 0; n < low.size(); ++n)
            low[n] = volume.values[n] < tau ? 1 : 0;
        const std::size_t nx = static_cast<std::size_t>(volume.dims[0]);
        const std::size_t nxy = nx * static_cast<std::size_t>(volume.dims[1]);
        for (int k = 0; k < mCells[2]; ++k)
            for (int j = 0; j < mCells[1]; ++j) {
                const std::uint8_t* r00 =
                    low.data() + static_cast<std::size_t>(k) * nxy + static_cast<std::size_t>(j) * nx;
                const std::uint8_t* r10 = r00 + nx;
                const std::uint8_t* r01 = r00 + nxy;
                const std::uint8_t* r11 = r01 + nx;
                std::uint8_t* out = mBackground.data() + index(0, j, k);
                for (int i = 0; i < mCells[0]; ++i)
                    out[i] =
                        r00[i] & r00[i + 1] & r10[i] & r10[i + 1] & r01[i] & r01[i + 1] & r11[i] & r11[i + 1];
            }
    }
    // The 3D prefix sum as three 1D passes (x, then y, then z), each over whole rows.
    const std::size_t px = static_cast<std::size_t>(mCells[0]) + 1,
                      py = static_cast<std::size_t>(mCells[1]) + 1,
                      pz = static_cast<std::size_t>(mCells[2]) + 1;
    mPrefix.assign(px * py * pz, 0);
    auto row = [&](std::size_t j, std::size_t k) { return mPrefix.data() + px * (j + py * k); };
    for (int k = 1; k <= mCells[2]; ++k)
        for (int j = 1; j <= mCells[1]; ++j) {
            std::uint32_t* out = row(static_cast<std::size_t>(j), static_cast<std::size_t>(k));
            const std::uint8_t* bg = mBackground.data() + index(0, j - 1, k - 1);
            for (int i = 1; i <= mCells[0]; ++i)
                out[i] = out[i - 1] + (bg[i - 1] ? 0u : 1u);
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
