// The walk's 64-byte Vot record: its polynomial stays within the stated maxError of the Vot's over the
// whole box, wherever the Vot was expanded, and maxError is as small as the header promises.
#include "WalkRecord.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace vots;
using namespace vots::render;

namespace {

// A Vot on a random box, expanded around a random point of it (centred when `centred`), whose terms of
// each degree reach about `scale` on the box.
fit::Vot randomVot(std::mt19937& rng, bool centred, double scale) {
    std::uniform_int_distribution<int> corner(0, 300), side(1, 16);
    std::uniform_real_distribution<double> unit(0.0, 1.0), coefficient(-1.0, 1.0);
    fit::Vot vot;
    double extent = 0.0;
    for (std::size_t a = 0; a < 3; ++a) {
        vot.box.lo[a] = corner(rng);
        vot.box.hi[a] = vot.box.lo[a] + side(rng);
        const double w = vot.box.hi[a] - vot.box.lo[a];
        vot.p[a] = static_cast<float>(vot.box.lo[a] + (centred ? 0.5 : unit(rng)) * w);
        extent = std::max(extent, w);
    }
    for (std::size_t k = 0; k < fit::MONOMIAL_COUNT; ++k)
        vot.c[k] = static_cast<float>(coefficient(rng) * scale / std::pow(extent, fit::monomialDegree(k)));
    vot.c[0] += static_cast<float>(10.0 * scale); // a value far from zero, as CT numbers are
    return vot;
}

// The record's polynomial at X (index space), as vot_walk.glsl evaluates it: around the box centre, in
// units of the half sides.
double evaluateRecord(const WalkRecord& record, const fit::Vot& vot, const std::array<double, 3>& x) {
    const std::array<double, fit::MONOMIAL_COUNT> d = walkRecordCoefficients(record);
    std::array<double, 3> u{};
    for (std::size_t a = 0; a < 3; ++a) {
        const double lo = vot.box.lo[a], hi = vot.box.hi[a];
        u[a] = (x[a] - 0.5 * (lo + hi)) / (0.5 * (hi - lo));
    }
    const std::array<double, fit::MONOMIAL_COUNT> monomials = fit::evaluateMonomials(u);
    double sum = 0.0;
    for (std::size_t k = 0; k < fit::MONOMIAL_COUNT; ++k)
        sum += d[k] * monomials[k];
    return sum;
}

// Largest |second- or third-order term| of the record's polynomial over the box.
double largestHigherTerm(const WalkRecord& record) {
    const std::array<double, fit::MONOMIAL_COUNT> d = walkRecordCoefficients(record);
    double largest = 0.0;
    for (std::size_t k = 4; k < fit::MONOMIAL_COUNT; ++k)
        largest = std::max(largest, std::abs(d[k]));
    return largest;
}

} // namespace

TEST(WalkRecord, PolynomialStaysWithinMaxErrorOverTheBox) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < 400; ++n) {
        const bool centred = n % 2 == 0;
        const double scale = std::pow(10.0, n % 7 - 2); // 0.01 .. 10^4
        const fit::Vot vot = randomVot(rng, centred, scale);
        const WalkRecord record = makeWalkRecord(vot);
        EXPECT_LE(record.maxError, 2.5e-4 * largestHigherTerm(record)) << n;
        // Float coefficients: a few units in the last place of the largest term.
        const double rounding = 1e-6 * 20.0 * scale;
        double worst = 0.0;
        for (int s = 0; s < 200; ++s) {
            std::array<double, 3> x{};
            for (std::size_t a = 0; a < 3; ++a) // corners included: u = +-1 is where errors add up
                x[a] = vot.box.lo[a] +
                       (s < 8 ? double((s >> a) & 1) : unit(rng)) * (vot.box.hi[a] - vot.box.lo[a]);
            worst = std::max(worst, std::abs(evaluateRecord(record, vot, x) - vot.evaluate(x)));
        }
        EXPECT_LE(worst, record.maxError + rounding) << n << (centred ? " centred" : " off-centre");
    }
}

TEST(WalkRecord, QuantisationErrorIsSmallBesideTheTermsItRounds) {
    // Not just a bound that holds: on random Vots the error is far below 2.5e-4 of the largest term,
    // as 16 roundings of at most half a quantum each rarely line up.
    std::mt19937 rng(6);
    double ratioSum = 0.0;
    constexpr int COUNT = 200;
    for (int n = 0; n < COUNT; ++n) {
        const WalkRecord record = makeWalkRecord(randomVot(rng, true, 100.0));
        ratioSum += record.maxError / largestHigherTerm(record);
    }
    EXPECT_LT(ratioSum / COUNT, 1.5e-4);
    EXPECT_GT(ratioSum / COUNT, 1e-5); // the terms really are rounded to 16 bits
}

TEST(WalkRecord, LinearVotIsExactAndBoxRoundTrips) {
    fit::Vot vot;
    vot.box.lo = {3, 65000, 0};
    vot.box.hi = {19, 65535, 1};
    vot.p = {3.f, 65000.f, 0.5f};
    vot.c.fill(0.f);
    vot.c[0] = 1000.f, vot.c[1] = 2.5f, vot.c[2] = -0.125f, vot.c[3] = 8.f;
    const WalkRecord record = makeWalkRecord(vot);
    EXPECT_EQ(record.maxError, 0.0);
    const auto& w = record.words;
    EXPECT_EQ(w[0], 3u | 65000u << 16);
    EXPECT_EQ(w[1], 0u | 19u << 16);
    EXPECT_EQ(w[2], 65535u | 1u << 16);
    const std::array<double, fit::MONOMIAL_COUNT> d = walkRecordCoefficients(record);
    EXPECT_DOUBLE_EQ(d[0], 1000.0 + 2.5 * 8.0 - 0.125 * 267.5); // value at the box centre
    EXPECT_DOUBLE_EQ(d[1], 2.5 * 8.0);                          // gradient times half sides
    EXPECT_DOUBLE_EQ(d[2], -0.125 * 267.5);
    EXPECT_DOUBLE_EQ(d[3], 8.0 * 0.5);
    for (std::size_t k = 4; k < fit::MONOMIAL_COUNT; ++k)
        EXPECT_EQ(d[k], 0.0) << k;
}
