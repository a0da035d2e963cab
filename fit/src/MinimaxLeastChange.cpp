// The least-change search of a box: the polynomial nearest least squares' whose residuals are within the
// target, by an active set of pinned points (docs/DESIGN.md §3, "Minimax acceptance", step 4).
#include "MinimaxSearch.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace vots::fit::minimax {
namespace {

/// The points a search pins: their whitened basis rows w = L^-1 phi (so the Gram matrix G = L L^T of the
/// samples becomes the identity), their start residuals and signs, and the Cholesky factor of the pins'
/// Gram matrix W^T W, grown one row per pin.
class Pins {
public:
    explicit Pins(int n) : mN(n) {}
    int size() const { return mCount; }

    /// Pins the point at `sign` * level. False, and nothing pinned, when its row is (nearly) in the span of
    /// the pinned rows: the pins would then ask for two values of one linear form.
    bool add(const double* whitened, double startResidual, double sign) {
        const int k = mCount;
        for (int a = 0; a < mN; ++a)
            mW[k][a] = whitened[a];
        mStart[k] = startResidual;
        mSign[k] = sign;
        for (int p = 0; p <= k; ++p) {
            double dot = 0.0;
            for (int a = 0; a < mN; ++a)
                dot += mW[p][a] * mW[k][a];
            mGram[p][k] = mGram[k][p] = dot;
        }
        if (!factorRow(k)) return false;
        ++mCount;
        return true;
    }

    /// The multipliers of the least change that puts every pin at its residual: solves (W^T W) lambda = d,
    /// d = start - sign * level, dropping each pin whose multiplier has the wrong sign (it would be inside
    /// the level without its pin) until none has. False when no pin is left.
    bool solve(double level, double* lambda) {
        for (;;) {
            for (int p = 0; p < mCount; ++p) {
                double sum = mStart[p] - mSign[p] * level;
                for (int q = 0; q < p; ++q)
                    sum -= mFactor[p][q] * lambda[q];
                lambda[p] = sum / mFactor[p][p];
            }
            for (int p = mCount - 1; p >= 0; --p) {
                double sum = lambda[p];
                for (int q = p + 1; q < mCount; ++q)
                    sum -= mFactor[q][p] * lambda[q];
                lambda[p] = sum / mFactor[p][p];
            }
            int release = -1;
            double mostNegative = 0.0;
            for (int p = 0; p < mCount; ++p)
                if (mSign[p] * lambda[p] < mostNegative) {
                    mostNegative = mSign[p] * lambda[p];
                    release = p;
                }
            if (release < 0) return mCount > 0;
            if (!remove(release)) return false;
        }
    }

    /// The whitened change sum_p lambda_p w_p.
    void change(const double* lambda, double* out) const {
        std::fill(out, out + mN, 0.0);
        for (int p = 0; p < mCount; ++p)
            for (int a = 0; a < mN; ++a)
                out[a] += lambda[p] * mW[p][a];
    }

private:
    /// Row k of the factor from the Gram matrix; false when its pivot vanishes.
    bool factorRow(int k) {
        double diagonal = mGram[k][k];
        for (int p = 0; p < k; ++p) {
            double sum = mGram[p][k];
            for (int q = 0; q < p; ++q)
                sum -= mFactor[p][q] * mFactor[k][q];
            mFactor[k][p] = sum / mFactor[p][p];
            diagonal -= mFactor[k][p] * mFactor[k][p];
        }
        if (!(diagonal > 1e-9 * mGram[k][k])) return false;
        mFactor[k][k] = std::sqrt(diagonal);
        return true;
    }

    bool remove(int r) {
        for (int p = r; p + 1 < mCount; ++p) {
            for (int a = 0; a < mN; ++a)
                mW[p][a] = mW[p + 1][a];
            mStart[p] = mStart[p + 1];
            mSign[p] = mSign[p + 1];
        }
        for (int p = r; p + 1 < mCount; ++p)
            for (int q = 0; q < mCount; ++q)
                mGram[p][q] = mGram[p + 1][q];
        for (int q = r; q + 1 < mCount; ++q)
            for (int p = 0; p + 1 < mCount; ++p)
                mGram[p][q] = mGram[p][q + 1];
        --mCount;
        for (int k = r; k < mCount; ++k) // (the rows before r keep their factor)
            if (!factorRow(k)) return false;
        return mCount > 0;
    }

    int mN;
    int mCount = 0;
    double mW[MAX_N][MAX_N];
    double mStart[MAX_N];
    double mSign[MAX_N];
    double mGram[MAX_N][MAX_N];
    double mFactor[MAX_N][MAX_N];
};

} // namespace

Whitening whiteningOf(const Geometry& g) {
    // Over a grid, sum_samples u^a v^b w^c is the product of one sum per axis.
    const Box& box = g.box();
    double powerSum[3][7] = {};
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < box.points(a); ++i) {
            const double u = g.scaled(a, 2 * (box.lo[a] + i));
            double power = 1.0;
            for (int p = 0; p < 7; ++p, power *= u)
                powerSum[a][p] += power;
        }
    const int n = g.n();
    Eigen::MatrixXd gram(n, n);
    for (int j = 0; j < n; ++j)
        for (int k = 0; k <= j; ++k) {
            const auto& ej = MONOMIAL_EXPONENTS[static_cast<std::size_t>(g.basis(j))];
            const auto& ek = MONOMIAL_EXPONENTS[static_cast<std::size_t>(g.basis(k))];
            gram(j, k) = gram(k, j) =
                powerSum[0][ej[0] + ek[0]] * powerSum[1][ej[1] + ek[1]] * powerSum[2][ej[2] + ek[2]];
        }
    Whitening w;
    Eigen::LLT<Eigen::MatrixXd> factor(gram);
    if (factor.info() != Eigen::Success) return w;
    const Eigen::MatrixXd inverse = factor.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
    if (!inverse.allFinite()) return w;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j <= i; ++j)
            w.inverseFactor[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = inverse(i, j);
    w.ok = true;
    return w;
}

MinimaxSolution findLeastChange(const Geometry& g, LeastChangePricing& pricing, const Whitening& white,
                                const std::array<double, MONOMIAL_COUNT>& start,
                                const MinimaxTarget& target) {
    MinimaxSolution solution;
    solution.result = MinimaxSolution::Result::NotFound;
    if (!white.ok) return solution;
    const int n = g.n();
    const double level = target.acceptBelow;
    const double pinAt = LEAST_CHANGE_PIN_LEVEL * level;
    const auto& L = white.inverseFactor;
    std::array<double, MAX_N> c0{}, c{};
    for (int j = 0; j < n; ++j)
        c0[static_cast<std::size_t>(j)] = start[static_cast<std::size_t>(g.basis(j))];
    c = c0;
    const auto residual = [n](const Point& p, const std::array<double, MAX_N>& coefficients) {
        double r = p.f;
        for (int j = 0; j < n; ++j)
            r -= p.phi[static_cast<std::size_t>(j)] * coefficients[static_cast<std::size_t>(j)];
        return r;
    };
    Pins pins(n);
    for (int round = 0; round < LEAST_CHANGE_ROUNDS; ++round) {
        ++solution.scans;
        Point beyond[LEAST_CHANGE_PINS_PER_ROUND];
        double largest = 0.0;
        const int count = pricing.beyond(c.data(), level, beyond, largest);
        if (count == 0) {
            for (int j = 0; j < n; ++j)
                solution.scaled[static_cast<std::size_t>(g.basis(j))] = c[static_cast<std::size_t>(j)];
            solution.maxResidual = largest;
            if (target.accept(solution.scaled)) solution.result = MinimaxSolution::Result::Found;
            return solution;
        }
        int taken = 0;
        for (int q = 0; q < count && pins.size() < n; ++q) {
            const Point& p = beyond[q];
            alignas(16) double whitened[MAX_N];
            for (int a = 0; a < n; ++a) {
                double sum = 0.0;
                for (int b = 0; b <= a; ++b)
                    sum += L[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] *
                           p.phi[static_cast<std::size_t>(b)];
                whitened[a] = sum;
            }
            // Pinned on the side it is beyond; the least change is measured from c0, so the pin holds the
            // residual c0 leaves there.
            taken += pins.add(whitened, residual(p, c0), residual(p, c) > 0 ? 1.0 : -1.0);
        }
        double lambda[MAX_N];
        if (taken == 0 || !pins.solve(pinAt, lambda)) return solution;
        // c = c0 + L^-T (sum_p lambda_p w_p)
        double change[MAX_N];
        pins.change(lambda, change);
        for (int j = 0; j < n; ++j) {
            double sum = 0.0;
            for (int a = j; a < n; ++a)
                sum += L[static_cast<std::size_t>(a)][static_cast<std::size_t>(j)] * change[a];
            c[static_cast<std::size_t>(j)] = c0[static_cast<std::size_t>(j)] + sum;
            if (!std::isfinite(c[static_cast<std::size_t>(j)])) return solution;
        }
    }
    return solution;
}

} // namespace vots::fit::minimax
