// Bernstein bounds of a Vot over its box: they contain every value of the polynomial on the box, are
// exact at the corners for a linear Vot, and equal hand-computed Bernstein coefficients of a cubic.
#include "VotBounds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace vots;
using namespace vots::render;

namespace {

double evaluate(const fit::Vot& vot, const double x[3]) {
    return vot.evaluate({x[0], x[1], x[2]});
}

fit::Vot randomVot(std::mt19937& rng) {
    std::uniform_int_distribution<int> corner(0, 40), side(1, 12);
    std::uniform_real_distribution<float> coefficient(-3.f, 3.f), unit(0.f, 1.f);
    fit::Vot vot;
    for (int a = 0; a < 3; ++a) {
        vot.box.lo[a] = corner(rng);
        vot.box.hi[a] = vot.box.lo[a] + side(rng);
        vot.p[a] = float(vot.box.lo[a]) + unit(rng) * float(vot.box.hi[a] - vot.box.lo[a]);
    }
    for (float& c : vot.c)
        c = coefficient(rng);
    return vot;
}

// A Vot with all coefficients zero on the box [lo, hi], expanded around p.
fit::Vot zeroVot(std::array<int, 3> lo, std::array<int, 3> hi, std::array<float, 3> p) {
    fit::Vot vot;
    vot.box.lo = lo;
    vot.box.hi = hi;
    vot.p = p;
    vot.c.fill(0.f);
    return vot;
}

} // namespace

TEST(VotBounds, ContainEveryValueOnTheBox) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 200; ++trial) {
        const fit::Vot vot = randomVot(rng);
        const VotBounds b = computeVotBounds(vot);
        double seenMin = INFINITY, seenMax = -INFINITY;
        constexpr int N = 9;
        for (int i = 0; i <= N; ++i)
            for (int j = 0; j <= N; ++j)
                for (int k = 0; k <= N; ++k) {
                    const int s[3] = {i, j, k};
                    double x[3];
                    for (int a = 0; a < 3; ++a)
                        x[a] = vot.box.lo[a] + (vot.box.hi[a] - vot.box.lo[a]) * double(s[a]) / N;
                    const double v = evaluate(vot, x);
                    seenMin = std::min(seenMin, v);
                    seenMax = std::max(seenMax, v);
                }
        const double tolerance = 1e-9 * (std::abs(seenMin) + std::abs(seenMax) + 1.0);
        EXPECT_LE(b.lower, seenMin + tolerance) << "trial " << trial;
        EXPECT_GE(b.upper, seenMax - tolerance) << "trial " << trial;
        EXPECT_GT(b.floatSlack, 0.0);
    }
}

TEST(VotBounds, LinearVotIsBoundedExactlyByItsCorners) {
    fit::Vot vot = zeroVot({2, 3, 4}, {6, 5, 9}, {3.5f, 4.f, 6.f});
    vot.c[0] = 10.f;                                   // value
    vot.c[1] = 2.f;                                    // d/dx
    vot.c[2] = -1.f;                                   // d/dy
    vot.c[3] = 0.5f;                                   // d/dz
    const double lo[3] = {2, 5, 4}, hi[3] = {6, 3, 9}; // the corners that minimise and maximise
    const VotBounds b = computeVotBounds(vot);
    EXPECT_NEAR(b.lower, evaluate(vot, lo), 1e-12);
    EXPECT_NEAR(b.upper, evaluate(vot, hi), 1e-12);
}

TEST(VotBounds, EqualTheBernsteinCoefficientsOfACubic) {
    // f = (x - p)^3 on x in [p - 1, p + 2]: with x - p = -1 + 3t, the Bernstein coefficients are
    // f(0) = -1, f(0) + f'(0)/3 = 2, f(1) - f'(1)/3 = -4 and f(1) = 8, so the bounds are [-4, 8] (wider
    // than the range [-1, 8]: the hull, not the range, is what the bound promises).
    fit::Vot vot = zeroVot({10, 0, 0}, {13, 1, 1}, {11.f, 0.f, 0.f});
    for (std::size_t m = 0; m < fit::MONOMIAL_COUNT; ++m)
        if (fit::MONOMIAL_EXPONENTS[m] == std::array<int, 3>{3, 0, 0}) vot.c[m] = 1.f;
    const VotBounds b = computeVotBounds(vot);
    EXPECT_NEAR(b.lower, -4.0, 1e-12);
    EXPECT_NEAR(b.upper, 8.0, 1e-12);
}
