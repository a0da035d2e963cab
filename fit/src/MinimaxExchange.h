// The exchange of a minimax fit: the simplex method on the dual LP, with the basis inverse kept explicitly.
#pragma once

#include "MinimaxLattice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vots::fit::minimax {

inline constexpr int REFACTOR_EVERY = 64; // pivots between fresh inverses of the basis
inline constexpr double PIVOT_TOLERANCE = 1e-9;
inline constexpr int MAX_N = static_cast<int>(MONOMIAL_COUNT) + 1;
inline constexpr int WIDTH = MAX_N + 1;

/// The simplex method on the dual LP
///     max sum_p s_p f_p x_p   s.t.  sum_p x_p s_p phi_p = 0,  sum_p x_p = 1,  x >= 0
/// whose basis holds n + 1 (point, sign) columns. Its multipliers y = (c, t) solve B^T y = cost: the
/// polynomial c has residual s_p t at each basic point, and t, the dual objective, is a lower bound of
/// the minimax error over any set of points that holds the basic ones. A point whose |residual| exceeds t
/// is a column with positive reduced cost |r| - t: pricing is a search for the worst residual. The basis
/// inverse is kept explicitly (at most 21 x 21), by columns, and updated by each pivot; every loop runs
/// along a column, so none is a chain of dependent additions.
class Exchange {
public:
    explicit Exchange(int n) : mN(n), mRows(n + 1) {}

    double t() const { return mY[mN]; }
    int pivots() const { return mPivots; }
    const double* coefficients() const { return mY; }
    /// phi holds MONOMIAL_COUNT values, 0 beyond n (where phi[n] = 0 meets y[n] = t).
    double residual(const double* phi, double f) const {
        double s0 = f, s1 = 0.0, s2 = 0.0, s3 = 0.0;
        for (std::size_t j = 0; j < MONOMIAL_COUNT; j += 4) {
            s0 -= phi[j] * mY[j];
            s1 -= phi[j + 1] * mY[j + 1];
            s2 -= phi[j + 2] * mY[j + 2];
            s3 -= phi[j + 3] * mY[j + 3];
        }
        return (s0 + s1) + (s2 + s3);
    }

    /// A first dual-feasible basis: n candidates whose basis rows are independent (in order, skipping
    /// one nearly in the span of those chosen before it), one more, and the signs and weights of the null
    /// vector of their n + 1 rows. candidates.phi(k, out) writes the n basis values of candidate k; .f(k)
    /// and .key(k) for k < candidates.size().
    template <typename Candidates> bool start(const Candidates& candidates) {
        const int n = mN;
        const int count = candidates.size();
        // Echelon rows E_k = (phi_{chosen k} - sum_{j<k} lower[k][j] E_j) / scale[k], each 1 at its pivot
        // column and 0 at the pivot columns of the rows before it.
        alignas(16) double echelon[MAX_N][WIDTH];
        double lower[MAX_N][MAX_N];
        double scale[MAX_N];
        int pivotColumn[MAX_N];
        int chosen[MAX_N];
        int rank = 0;
        double factors[MAX_N];
        auto isChosen = [&](int c) { return std::find(chosen, chosen + rank, c) != chosen + rank; };
        for (double threshold : {0.05, 1e-7}) {
            for (int c = 0; c < count && rank < n; ++c) {
                if (isChosen(c)) continue;
                alignas(16) double v[WIDTH] = {};
                candidates.phi(c, v);
                double norm0 = 0.0;
                for (int j = 0; j < n; ++j)
                    norm0 = std::max(norm0, std::abs(v[j]));
                if (norm0 == 0.0) continue;
                for (int k = 0; k < rank; ++k) {
                    const double factor = v[pivotColumn[k]];
                    factors[k] = factor;
                    if (factor == 0.0) continue;
#pragma GCC unroll 22
                    for (int j = 0; j < WIDTH; ++j)
                        v[j] -= factor * echelon[k][j];
                }
                int best = 0;
                for (int j = 1; j < n; ++j)
                    if (std::abs(v[j]) > std::abs(v[best])) best = j;
                if (!(std::abs(v[best]) > threshold * norm0)) continue;
                const double inverse = 1.0 / v[best];
                for (int j = 0; j < WIDTH; ++j)
                    echelon[rank][j] = v[j] * inverse;
                echelon[rank][best] = 1.0;
                std::copy(factors, factors + rank, lower[rank]);
                scale[rank] = v[best];
                pivotColumn[rank] = best;
                chosen[rank++] = c;
            }
        }
        if (rank < n) return false;
        int extra = 0;
        while (extra < count && isChosen(extra))
            ++extra;
        if (extra == count) return false;
        chosen[n] = extra;

        // sigma = (w, 1) with sum_i w_i phi_{chosen i} = -phi_extra, so sum_p sigma_p phi_p = 0 over the
        // n + 1 points. phi_extra = sum_k b_k E_k (its elimination), and (D + L) E = Phi with D =
        // diag(scale), L = lower: w = -(D + L)^{-T} b, one back substitution.
        double w[MAX_N];
        {
            alignas(16) double v[WIDTH] = {};
            candidates.phi(extra, v);
            double b[MAX_N];
            for (int k = 0; k < n; ++k) {
                b[k] = v[pivotColumn[k]];
                if (b[k] == 0.0) continue;
                for (int j = 0; j < WIDTH; ++j)
                    v[j] -= b[k] * echelon[k][j];
            }
            for (int i = n - 1; i >= 0; --i) {
                double sum = b[i];
                for (int k = i + 1; k < n; ++k)
                    sum -= lower[k][i] * w[k];
                w[i] = sum / scale[i];
            }
            for (int i = 0; i < n; ++i) {
                w[i] = -w[i];
                if (!std::isfinite(w[i])) return false;
            }
        }
        // sigma and -sigma are both null vectors; the one with sigma . f >= 0 starts at t >= 0, the
        // other at -t, which would take pivots to undo.
        double dot = candidates.f(extra);
        for (int i = 0; i < n; ++i)
            dot += w[i] * candidates.f(chosen[i]);
        const double orientation = dot >= 0.0 ? 1.0 : -1.0;
        for (int i = 0; i <= n; ++i) {
            const double sigma = orientation * (i < n ? w[i] : 1.0);
            std::fill(mPhi[i], mPhi[i] + WIDTH, 0.0);
            candidates.phi(chosen[i], mPhi[i]);
            mF[i] = candidates.f(chosen[i]);
            mKey[i] = candidates.key(chosen[i]);
            mSign[i] = sigma >= 0.0 ? 1.0 : -1.0;
            mCost[i] = mSign[i] * mF[i];
        }
        return refactor();
    }

    /// Whether column (point, sign) is basic. The other sign's column of a basic point can enter: it has
    /// reduced cost -2t, positive while t is negative (a first basis can have t < 0).
    bool inBasis(std::uint64_t key, double sign) const {
        for (int i = 0; i < mRows; ++i)
            if (mKey[i] == key && mSign[i] == sign) return true;
        return false;
    }

    /// Brings the column of the point (phi: MONOMIAL_COUNT values, 0 beyond n; f, key) with the sign of its
    /// residual r into the basis; the point that leaves is written to `left` when given.
    bool pivot(const double* phi, double f, std::uint64_t key, double r, Point* left) {
        const int n = mN, rows = mRows;
        const double s = r >= 0.0 ? 1.0 : -1.0;
        // d = B^{-1} a for the entering column a = (s phi, 1), column by column.
        alignas(16) double d[WIDTH];
        for (int i = 0; i < WIDTH; ++i)
            d[i] = mInverse[n][i];
        for (int j = 0; j < n; ++j) {
            const double aj = s * phi[j];
            if (aj == 0.0) continue;
            const double* column = mInverse[j];
#pragma GCC unroll 22
            for (int i = 0; i < WIDTH; ++i)
                d[i] += aj * column[i];
        }
        int leave = -1;
        double best = std::numeric_limits<double>::infinity();
        for (int i = 0; i < rows; ++i) {
            if (d[i] <= PIVOT_TOLERANCE) continue;
            const double ratio = mX[i] / d[i];
            // Ties (degenerate steps, x = 0) go to the largest pivot, the most stable one.
            if (ratio < best - 1e-15 || (ratio <= best + 1e-15 && d[i] > d[leave])) {
                best = std::min(best, ratio);
                leave = i;
            }
        }
        if (leave < 0) return false;
        const double reducedCost = s * r - t();
        const double theta = std::max(0.0, mX[leave] / d[leave]);
        for (int i = 0; i < rows; ++i)
            mX[i] = std::max(0.0, mX[i] - theta * d[i]);
        mX[leave] = theta;
        // Row `leave` of the inverse is divided by the pivot, and d times it taken from every other row.
        const double inverse = 1.0 / d[leave];
        d[leave] = 0.0;
        for (int j = 0; j < rows; ++j) {
            double* column = mInverse[j];
            const double pivotEntry = column[leave] * inverse;
#pragma GCC unroll 22
            for (int i = 0; i < WIDTH; ++i)
                column[i] -= pivotEntry * d[i];
            column[leave] = pivotEntry;
            // y' = y + (reduced cost) * (the new inverse's row of the entering column).
            mY[j] += reducedCost * pivotEntry;
        }
        if (left) {
            left->key = mKey[leave];
            left->f = mF[leave];
            std::copy(mPhi[leave], mPhi[leave] + MONOMIAL_COUNT, left->phi.begin());
        }
        std::copy(phi, phi + MONOMIAL_COUNT, mPhi[leave]);
        mF[leave] = f;
        mKey[leave] = key;
        mSign[leave] = s;
        mCost[leave] = s * f;
        ++mPivots;
        if (mPivots % REFACTOR_EVERY == 0) return refactor();
        return std::isfinite(mY[n]);
    }

private:
    /// A fresh inverse of the basis, and x and y from it: Gauss-Jordan elimination with partial pivoting
    /// of B^T, whose inverse, (B^{-1})^T, row by row is B^{-1} column by column.
    bool refactor() {
        const int n = mN, rows = mRows;
        double(*a)[WIDTH] = mInverse;
        for (int i = 0; i < WIDTH; ++i)
            for (int j = 0; j < WIDTH; ++j)
                a[i][j] = 0.0;
        for (int i = 0; i < rows; ++i) {
            for (int j = 0; j < n; ++j)
                a[i][j] = mSign[i] * mPhi[i][j];
            a[i][n] = 1.0;
        }
        int swapped[MAX_N];
        for (int k = 0; k < rows; ++k) {
            int p = k;
            for (int i = k + 1; i < rows; ++i)
                if (std::abs(a[i][k]) > std::abs(a[p][k])) p = i;
            if (!(std::abs(a[p][k]) > 1e-13)) return false;
            swapped[k] = p;
            if (p != k)
                for (int j = 0; j < WIDTH; ++j)
                    std::swap(a[p][j], a[k][j]);
            const double inverse = 1.0 / a[k][k];
            a[k][k] = 1.0;
            // The pivot row in a local copy, which no store to the other rows can alias: it stays in
            // registers.
            alignas(16) double pivotRow[WIDTH];
            for (int j = 0; j < WIDTH; ++j)
                pivotRow[j] = a[k][j] *= inverse;
            for (int i = 0; i < rows; ++i) {
                if (i == k) continue;
                const double factor = a[i][k];
                if (factor == 0.0) continue;
                a[i][k] = 0.0;
#pragma GCC unroll 22
                for (int j = 0; j < WIDTH; ++j)
                    a[i][j] -= factor * pivotRow[j];
            }
        }
        for (int k = rows - 1; k >= 0; --k)
            if (swapped[k] != k)
                for (int i = 0; i < rows; ++i)
                    std::swap(a[i][k], a[i][swapped[k]]);
        // x = B^{-1} e_n: the inverse's last column; y = B^{-T} cost.
        for (int i = 0; i < rows; ++i)
            mX[i] = std::max(0.0, mInverse[n][i]);
        for (int j = 0; j < WIDTH; ++j)
            mY[j] = 0.0;
        for (int j = 0; j < rows; ++j) {
            double sum = 0.0;
            for (int i = 0; i < rows; ++i)
                sum += mCost[i] * mInverse[j][i];
            mY[j] = sum;
            if (!std::isfinite(sum)) return false;
        }
        return true;
    }

    int mN;
    int mRows;
    // mInverse[j][i] = (B^{-1})_{ij}: column j of the inverse, padded to an even WIDTH with 0.
    alignas(16) double mInverse[WIDTH][WIDTH];
    alignas(16) double mPhi[MAX_N][WIDTH];
    double mF[MAX_N];
    std::uint64_t mKey[MAX_N];
    double mSign[MAX_N];
    double mX[MAX_N];
    double mCost[MAX_N];
    alignas(16) double mY[WIDTH] = {};
    int mPivots = 0;
};

} // namespace vots::fit::minimax
