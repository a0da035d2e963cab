// The two methods of a minimax fit, and what their steps share: the cell points' bound, a step's end.
#pragma once

#include "MinimaxExchange.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>

namespace vots::fit::minimax {

using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MAX_N, 1>;

/// An upper bound of |residual| at the cell points beyond the largest at the samples: for a cubic, the
/// mean of P at the 2, 4 or 8 corners of an edge, face or cell is P at its centre plus a/8 of the sum of the
/// second derivatives along its a half axes, and the reference there is the mean of the samples; second
/// derivatives are affine in position, so their sums take their largest magnitude at a corner of the box.
/// `c` holds the coefficients of the basis over scaled coordinates. A relative 1e-9 and 1e-12 scale cover
/// the rounding of the residuals computed with them.
inline double cellBound(const Geometry& g, const double* c, double scale) {
    const Box& box = g.box();
    // Second derivative along axis a, in index units: (grad0 + sum_b grad[b] u_b) / half_a^2.
    double second[3][4] = {};
    for (int j = 0; j < g.n(); ++j) {
        const auto& e = MONOMIAL_EXPONENTS[static_cast<std::size_t>(g.basis(j))];
        for (int a = 0; a < 3; ++a) {
            if (e[a] < 2) continue;
            std::array<int, 3> rest = e;
            rest[a] -= 2;
            const double factor = c[j] * e[a] * (e[a] - 1);
            const int term = rest[0] ? 1 : rest[1] ? 2 : rest[2] ? 3 : 0; // the degree is at most 3
            second[a][term] += factor;
        }
    }
    double inverseHalfSquared[3];
    for (int a = 0; a < 3; ++a) {
        const double half = 0.5 * box.cells(a);
        inverseHalfSquared[a] = 1.0 / (half * half);
    }
    double largest = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        double d[3];
        const double u[3] = {(corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0, (corner & 4) ? 1.0 : -1.0};
        for (int a = 0; a < 3; ++a)
            d[a] = (second[a][0] + second[a][1] * u[0] + second[a][2] * u[1] + second[a][3] * u[2]) *
                   inverseHalfSquared[a];
        // Edges: one axis; faces: two (MINIMAX_FACE_CENTRES); cells: three.
        largest =
            std::max({largest, std::abs(d[0]), std::abs(d[1]), std::abs(d[2]), std::abs(d[0] + d[1] + d[2])});
        if (MINIMAX_FACE_CENTRES)
            largest =
                std::max({largest, std::abs(d[0] + d[1]), std::abs(d[0] + d[2]), std::abs(d[1] + d[2])});
    }
    const double bound = largest / 8.0;
    return bound * (1.0 + 1e-9) + 1e-12 * scale;
}

/// The end of an exchange: its polynomial (coefficients y of the basis) is the minimax one, with this largest
/// residual.
inline void converged(const Geometry& g, const double* y, double largest, MinimaxSolution& solution) {
    for (int j = 0; j < g.n(); ++j)
        solution.scaled[static_cast<std::size_t>(g.basis(j))] = y[j];
    solution.maxResidual = largest;
    solution.result = MinimaxSolution::Result::Converged;
}

/// The least-change search (MinimaxLeastChange.cpp) pins at most this many of the worst points beyond the
/// target per round, for at most this many rounds: most searches that find a polynomial find it within
/// three, and more rounds find little more (bench/RESULTS.md, "The least-change search").
inline constexpr int LEAST_CHANGE_PINS_PER_ROUND = 4;
inline constexpr int LEAST_CHANGE_ROUNDS = 16;
/// A pinned point's residual is held at this fraction of the target: inside it, so that the rounding of
/// the change cannot take the point past the target.
inline constexpr double LEAST_CHANGE_PIN_LEVEL = 0.999;

/// L^-1 for the Cholesky factor L L^T of the Gram matrix of a box's basis rows at its samples: in the
/// rows L^-1 phi the least-squares metric is the Euclidean one.
struct Whitening {
    std::array<std::array<double, MAX_N>, MAX_N> inverseFactor{}; // lower triangular
    bool ok = false;                                              // false for a singular Gram matrix
};
/// From the box's shape alone (the samples are a grid).
Whitening whiteningOf(const Geometry& g);

/// How a least-change search reads a box's points (MinimaxDense.cpp, MinimaxScan.cpp).
class LeastChangePricing {
public:
    /// Up to LEAST_CHANGE_PINS_PER_ROUND points whose residual under the coefficients c (of the basis)
    /// passes `level`, worst first, into `out`; their count. `largest` is the largest |residual| priced.
    /// The cell points are priced only when no sample passes the level and the curvature bound
    /// (cellBound) does not answer for them.
    virtual int beyond(const double* c, double level, Point* out, double& largest) = 0;

protected:
    ~LeastChangePricing() = default;
};

/// The polynomial nearest `start` (the least-squares one) in the least-squares metric whose residuals are
/// within target.acceptBelow at every point, when a search of LEAST_CHANGE_ROUNDS finds one and the
/// target's accept takes it (Found); else NotFound, which proves nothing (MinimaxLeastChange.cpp).
MinimaxSolution findLeastChange(const Geometry& g, LeastChangePricing& pricing, const Whitening& whitening,
                                const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target);

/// The exchange of a box of at most MINIMAX_DENSE_POINTS samples (MinimaxDense.cpp).
MinimaxSolution fitDense(const Volume& volume, const Geometry& g, Certify points,
                         const std::array<double, MONOMIAL_COUNT>& start);
/// The exchange of a larger box, scanned for its worst residuals (MinimaxScan.cpp).
MinimaxSolution fitByScans(const Volume& volume, const Geometry& g, Certify points,
                           const std::array<double, MONOMIAL_COUNT>& start);
/// The least-change search of a small box (MinimaxDense.cpp) and of a larger one (MinimaxScan.cpp).
MinimaxSolution findDense(const Volume& volume, const Geometry& g, Certify points,
                          const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target);
MinimaxSolution findByScans(const Volume& volume, const Geometry& g, Certify points,
                            const std::array<double, MONOMIAL_COUNT>& start, const MinimaxTarget& target);

} // namespace vots::fit::minimax
