// The points of a minimax fit: the box's basis over scaled coordinates, and the values on its lattice.
#pragma once

#include "Minimax.h"
#include "SampleAccess.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace vots::fit::minimax {

// The worst residual of each sign in each of REGIONS^3 parts of the box joins the pool after a scan, so
// one scan feeds many pivots.
inline constexpr int REGIONS = 3;
inline constexpr int REGION_COUNT = REGIONS * REGIONS * REGIONS;

/// A point of the box: a grid sample, or a cell centre or edge midpoint (odd doubled coordinates).
struct Point {
    std::uint64_t key = 0;                    // keyOf(twice the index coordinates)
    double f = 0.0;                           // the sample, or the trilinear value there
    std::array<double, MONOMIAL_COUNT> phi{}; // the basis at the point (the first n entries)
};

inline std::uint64_t keyOf(const std::array<int, 3>& twice) {
    return static_cast<std::uint64_t>(twice[0]) << 42 | static_cast<std::uint64_t>(twice[1]) << 21 |
           static_cast<std::uint64_t>(twice[2]);
}

/// Coefficients of a polynomial in scaled coordinates as a tensor: t[ax][ay][az] multiplies u^ax v^ay w^az.
using Tensor = std::array<std::array<std::array<double, 4>, 4>, 4>;

class Geometry {
public:
    Geometry(const Box& box, std::uint32_t mask) : mBox(box), mMask(mask) {
        for (int a = 0; a < 3; ++a) {
            mCentre[a] = 0.5 * (box.lo[a] + box.hi[a]);
            mHalf[a] = 0.5 * (box.hi[a] - box.lo[a]);
        }
        for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
            if (mask & (1u << i)) mBasis[static_cast<std::size_t>(mN++)] = static_cast<int>(i);
    }
    const Box& box() const { return mBox; }
    std::uint32_t mask() const { return mMask; }
    int n() const { return mN; }
    int basis(int j) const { return mBasis[static_cast<std::size_t>(j)]; }
    double scaled(int axis, int twice) const { return (0.5 * twice - mCentre[axis]) / mHalf[axis]; }
    /// Which third of the box along the axis holds the point.
    int region(int axis, int twice) const {
        const int offset = twice - 2 * mBox.lo[axis];
        return std::min(REGIONS - 1, offset * REGIONS / (2 * mBox.cells(axis)));
    }
    Point point(const std::array<int, 3>& twice, double f) const {
        Point p;
        p.key = keyOf(twice);
        p.f = f;
        double pw[3][4];
        for (int a = 0; a < 3; ++a) {
            const double u = scaled(a, twice[a]);
            pw[a][0] = 1.0;
            pw[a][1] = u;
            pw[a][2] = u * u;
            pw[a][3] = u * u * u;
        }
        for (int j = 0; j < mN; ++j) {
            const auto& e = MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis(j))];
            p.phi[static_cast<std::size_t>(j)] = pw[0][e[0]] * pw[1][e[1]] * pw[2][e[2]];
        }
        return p;
    }
    Tensor tensor(const double* c) const {
        Tensor t{};
        for (int j = 0; j < mN; ++j) {
            const auto& e = MONOMIAL_EXPONENTS[static_cast<std::size_t>(basis(j))];
            t[e[0]][e[1]][e[2]] = c[j];
        }
        return t;
    }

private:
    Box mBox;
    std::uint32_t mMask;
    std::array<double, 3> mCentre{}, mHalf{};
    std::array<int, MONOMIAL_COUNT> mBasis{};
    int mN = 0;
};

/// The trilinear value at a point of the half-integer lattice (doubled coordinates): the mean of the
/// corners of its edge, face or cell, x fastest, as BoxFitter::certify sums it.
template <typename T>
inline double latticeValue(const Volume& volume, const T* values, int tx, int ty, int tz) {
    const auto* base = values + volume.indexOf(tx >> 1, ty >> 1, tz >> 1);
    const std::size_t dy = static_cast<std::size_t>(volume.dims[0]);
    const std::size_t dz = dy * static_cast<std::size_t>(volume.dims[1]);
    const auto at = [base](std::size_t k) -> double { return sampleAsFloat(base[k]); };
    // The corners summed in that order, one case per kind of point (each half axis doubles the corners).
    switch ((tx & 1) | (ty & 1) << 1 | (tz & 1) << 2) {
    case 0:
        return at(0);
    case 1:
        return 0.5 * (at(0) + at(1));
    case 2:
        return 0.5 * (at(0) + at(dy));
    case 4:
        return 0.5 * (at(0) + at(dz));
    case 3:
        return (at(0) + at(1) + at(dy) + at(dy + 1)) / 4;
    case 5:
        return (at(0) + at(1) + at(dz) + at(dz + 1)) / 4;
    case 6:
        return (at(0) + at(dy) + at(dz) + at(dz + dy)) / 4;
    default:
        return (at(0) + at(1) + at(dy) + at(dy + 1) + at(dz) + at(dz + 1) + at(dz + dy) + at(dz + dy + 1)) /
               8;
    }
}

/// Whether the minimax fit of a Certify::Cells fit holds this point of the half-integer lattice besides the
/// samples: the certified edge midpoints and cell centres, and the face centres (MINIMAX_FACE_CENTRES).
inline bool isCellPoint(int halves) {
    return halves == 1 || halves == 3 || (MINIMAX_FACE_CENTRES && halves == 2);
}

/// The value a point stands for: the sample, or the trilinear value there (latticeValue).
inline double referenceAt(const Volume& volume, const std::array<int, 3>& twice) {
    return visitSamples(volume, [&](const auto* values) {
        return latticeValue(volume, values, twice[0], twice[1], twice[2]);
    });
}

} // namespace vots::fit::minimax
