// Taylor basis accessors: value, gradient, Hessian and third derivatives against the polynomial itself.
#include "vots/fit/Vot.h"

#include <gtest/gtest.h>

#include <random>

using namespace vots::fit;

namespace {

Vot randomVot(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-2.f, 2.f);
    Vot v;
    v.box = Box{{0, 0, 0}, {4, 4, 4}};
    v.p = {2.f, 1.5f, 2.5f};
    for (auto& c : v.c)
        c = u(rng);
    return v;
}

} // namespace

TEST(VotAccessors, GradientMatchesCentralDifferences) {
    const Vot v = randomVot(1);
    const std::array<double, 3> x{1.3, 2.2, 0.7};
    const auto g = v.computeGradient(x);
    const double h = 1e-4;
    for (int a = 0; a < 3; ++a) {
        auto xp = x, xm = x;
        xp[a] += h;
        xm[a] -= h;
        EXPECT_NEAR(g[a], (v.evaluate(xp) - v.evaluate(xm)) / (2 * h), 1e-6);
    }
}

TEST(VotAccessors, HessianMatchesDifferencesOfGradient) {
    const Vot v = randomVot(2);
    const std::array<double, 3> x{0.4, 3.1, 1.9};
    const auto hess = v.computeHessian(x);
    const double h = 1e-4;
    for (int a = 0; a < 3; ++a) {
        auto xp = x, xm = x;
        xp[a] += h;
        xm[a] -= h;
        const auto gp = v.computeGradient(xp), gm = v.computeGradient(xm);
        for (int b = 0; b < 3; ++b)
            EXPECT_NEAR(hess[b * 3 + a], (gp[b] - gm[b]) / (2 * h), 1e-6);
    }
}

TEST(VotAccessors, DerivativesFollowDesignCoefficientRules) {
    Vot v;
    v.c[static_cast<std::size_t>(monomialIndex(2, 0, 0))] = 3.f;  // H_xx = 2 c_xx
    v.c[static_cast<std::size_t>(monomialIndex(1, 1, 0))] = 5.f;  // H_xy = c_xy
    v.c[static_cast<std::size_t>(monomialIndex(2, 1, 0))] = 7.f;  // T_xxy = 2 c_xxy
    v.c[static_cast<std::size_t>(monomialIndex(1, 1, 1))] = 11.f; // T_xyz = c_xyz
    v.c[static_cast<std::size_t>(monomialIndex(3, 0, 0))] = 13.f; // T_xxx = 6 c_xxx
    const auto h = v.computeHessian({0.0, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(h[0], 6.0);
    EXPECT_DOUBLE_EQ(h[1], 5.0);
    const auto t = v.thirdDerivatives();
    EXPECT_DOUBLE_EQ(t[0 * 9 + 0 * 3 + 1], 14.0);
    EXPECT_DOUBLE_EQ(t[1 * 9 + 0 * 3 + 0], 14.0); // symmetric
    EXPECT_DOUBLE_EQ(t[0 * 9 + 1 * 3 + 2], 11.0);
    EXPECT_DOUBLE_EQ(t[0], 78.0);
    EXPECT_EQ(v.effectiveDegree(), 3);
}

TEST(Monomials, CanonicalOrderIsTheDesignOrder) {
    const char* expected[] = {"1",   "x",   "y",   "z",   "xx",  "yy",  "zz",  "xy",  "xz",  "yz",
                              "xxx", "yyy", "zzz", "xxy", "xxz", "xyy", "yyz", "xzz", "yzz", "xyz"};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        EXPECT_STREQ(MONOMIAL_NAMES[i], expected[i]);
        int counts[3] = {0, 0, 0};
        for (const char* p = expected[i]; *p; ++p)
            if (*p != '1') ++counts[*p - 'x'];
        EXPECT_EQ(MONOMIAL_EXPONENTS[i][0], counts[0]) << expected[i];
        EXPECT_EQ(MONOMIAL_EXPONENTS[i][1], counts[1]) << expected[i];
        EXPECT_EQ(MONOMIAL_EXPONENTS[i][2], counts[2]) << expected[i];
    }
}
