// Minimax acceptance (docs/DESIGN.md §3, "Minimax"; white box, fit/src): a box least squares refuses is kept,
// by least squares with its residuals centred, or by the least-change search (a small box and a large one).
#include "BoxFit.h"
#include "Minimax.h"
#include "MinimaxChecks.h"
#include "SyntheticFields.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vots::fit;
using namespace vots::test;

namespace {

/// A polynomial plus +-`amplitude` eps: minus everywhere but plus at one corner. The polynomial itself is
/// within amplitude eps of every sample, and of every trilinear value between them when it is of degree 1;
/// least squares spreads the corner over the whole box and misses it by 2 amplitude eps times one minus its
/// leverage (0.12 here): 1.23 eps for amplitude 0.7, under the gate (MINIMAX_GATE) but over eps.
Volume cornerSpike(double eps, double amplitude, int degree) {
    const std::array<int, 3> dims{9, 9, 9};
    const vots::test::Polynomial p = vots::test::randomPolynomial(degree, dims, 11u, 400.0);
    return sampleVolume(dims, [&](int x, int y, int z) {
        const bool corner = x == 0 && y == 0 && z == 0;
        return p(x, y, z) + (corner ? amplitude : -amplitude) * eps;
    });
}

/// A polynomial plus `amplitude` eps at the corner (0, 0, 0) of a cube of side^3 samples, minus it at the
/// opposite one and nothing elsewhere: least squares misses the two corners by about the same amount, one up
/// and one down, so moving its constant gains nothing; the polynomial plus the plane that is +amplitude/2 eps
/// at the first corner and -amplitude/2 eps at the other is within amplitude/2 eps of every sample.
Volume opposedCornerSpikes(double eps, double amplitude, int degree, int side = 9) {
    const std::array<int, 3> dims{side, side, side};
    const vots::test::Polynomial p = vots::test::randomPolynomial(degree, dims, 11u, 400.0);
    return sampleVolume(dims, [&](int x, int y, int z) {
        const double spike = x + y + z == 0 ? amplitude : x + y + z == 3 * (side - 1) ? -amplitude : 0.0;
        return p(x, y, z) + spike * eps;
    });
}

/// The largest |Vot - sample| over the box, recomputed here from the outcome's float coefficients.
double worstSample(const Volume& volume, const Box& box, const BoxOutcome& outcome) {
    Vot vot;
    vot.box = box;
    vot.p = outcome.p;
    vot.c = outcome.c;
    double worst = 0.0;
    for (int z = box.lo[2]; z <= box.hi[2]; ++z)
        for (int y = box.lo[1]; y <= box.hi[1]; ++y)
            for (int x = box.lo[0]; x <= box.hi[0]; ++x)
                worst = std::max(worst, std::abs(evaluate(vot, x, y, z) - volume.at(x, y, z)));
    return worst;
}

/// One minimax decision of a box at a uniform eps, as the merge asks for it: the outcome and the record.
struct Decided {
    BoxOutcome outcome;
    BoxRecord record;
};
Decided decideByMinimax(const Volume& volume, const Box& box, float eps) {
    FitCounters counters;
    const BoxFitter minimax(volume, 3, Certify::Samples, FitNorm::Minimax);
    Decided d;
    d.outcome = minimax.decide(box, EpsField(eps), d.record, counters);
    return d;
}

} // namespace

TEST(Minimax, KeepsWholeABoxThatACubicFitsWithinEpsButLeastSquaresDoesNot) {
    const float eps = 10.f;
    const Volume volume = opposedCornerSpikes(eps, 1.4, 3);
    const Box box{{0, 0, 0}, {8, 8, 8}};
    const EpsField field(eps);
    FitCounters counters;

    const BoxFitter lsq(volume, 3, Certify::Samples, FitNorm::Lsq);
    const BoxOutcome byLsq = lsq.fit(box, field, counters);
    EXPECT_FALSE(byLsq.accepted) << "least squares must refuse the box for the test to mean anything";

    const auto [byMinimax, record] = decideByMinimax(volume, box, eps);
    ASSERT_TRUE(byMinimax.accepted);
    EXPECT_GT(record.centredHalfRange, eps) << "centring must not be enough for the search to be tested";
    EXPECT_EQ(record.state, BoxRecord::Minimax::Found);
    EXPECT_LE(byMinimax.errSamples, eps);
    const double worst = worstSample(volume, box, byMinimax);
    EXPECT_LE(worst, eps);
    EXPECT_GE(byMinimax.errSamples, worst * (1.0 - 1e-6)); // the recorded error bounds the samples'

    // Whole volumes: the split cuts the box with least squares, the merge puts it together again.
    const FitResult fitLsq = fitVotSpace(volume, options(eps, 3, FitNorm::Lsq));
    const FitResult fitMinimax = fitVotSpace(volume, options(eps, 3, FitNorm::Minimax));
    EXPECT_GT(fitLsq.space.vots.size(), 1u);
    ASSERT_EQ(fitMinimax.space.vots.size(), 1u);
    EXPECT_EQ(fitMinimax.space.vots[0].box, box);
    EXPECT_TRUE(verifyVotSpace(fitMinimax.space, volume).ok);
    EXPECT_GT(fitMinimax.stats.minimaxAccepted, 0u);
}

TEST(Minimax, TriesLeastSquaresWithItsResidualsCentredBeforeAnExchange) {
    // One corner up, the rest down: least squares misses the corner by 1.23 eps and the other samples by
    // little, all below it; with its constant moved to the middle of that range it is within eps.
    const float eps = 10.f;
    const Volume volume = cornerSpike(eps, 0.7, 3);
    const Box box{{0, 0, 0}, {8, 8, 8}};
    const auto [centred, record] = decideByMinimax(volume, box, eps);
    ASSERT_TRUE(centred.accepted);
    EXPECT_FALSE(record.lsq.accepted);
    EXPECT_EQ(record.state, BoxRecord::Minimax::Centred);
    EXPECT_LE(record.centredHalfRange, eps);
    EXPECT_LE(worstSample(volume, box, centred), eps);
    EXPECT_GT(worstSample(volume, box, record.lsq), eps);
    // The least-squares polynomial but for its constant.
    for (std::size_t i = 1; i < MONOMIAL_COUNT; ++i)
        EXPECT_EQ(centred.c[i], record.lsq.c[i]) << "monomial " << i;
    EXPECT_NE(centred.c[0], record.lsq.c[0]);

    const FitResult fit = fitVotSpace(volume, options(eps, 3, FitNorm::Minimax));
    ASSERT_EQ(fit.space.vots.size(), 1u);
    EXPECT_TRUE(verifyVotSpace(fit.space, volume).ok);
    EXPECT_GT(fit.stats.centredAccepted, 0u);
    EXPECT_EQ(fit.stats.minimaxFits, 0u) << "no search was needed";
}

TEST(Minimax, KeepsSuchABoxWholeWhenCertifiedAtTheCellsToo) {
    // A plane plus +-0.7 eps: the trilinear values between the samples are means of theirs, so the plane is
    // within 0.7 eps everywhere (under the cells' target of 0.9 eps), and least squares is not within eps.
    const float eps = 10.f;
    const Volume volume = cornerSpike(eps, 0.7, 1);
    const Box box{{0, 0, 0}, {8, 8, 8}};
    FitCounters counters;
    const BoxFitter lsq(volume, 3, Certify::Cells, FitNorm::Lsq);
    EXPECT_FALSE(lsq.fit(box, EpsField(eps), counters).accepted);
    const FitResult fitLsq = fitVotSpace(volume, options(eps, 3, FitNorm::Lsq, Certify::Cells));
    const FitResult fitMinimax = fitVotSpace(volume, options(eps, 3, FitNorm::Minimax, Certify::Cells));
    EXPECT_GT(fitLsq.space.vots.size(), 1u);
    ASSERT_EQ(fitMinimax.space.vots.size(), 1u);
    const Independent check = recompute(fitMinimax.space, volume, EpsField(eps), -INFINITY, true);
    EXPECT_EQ(check.beyondEps, 0u);
    EXPECT_LE(check.worstCellPoint, 1.0);
}

TEST(Minimax, KeepsWholeASmallBoxByTheLeastChangeSearch) {
    // The opposed spikes in a box of 6^3 samples, small enough for the dense method (the box above is
    // scanned): least squares misses both spikes by 1.1 eps, centring gains nothing, and the polynomial plus
    // a plane is within 0.9 eps of every sample.
    const float eps = 10.f;
    const Volume volume = opposedCornerSpikes(eps, 1.8, 3, 6);
    const Box box{{0, 0, 0}, {5, 5, 5}};
    ASSERT_LE(box.pointCount(), MINIMAX_DENSE_POINTS);
    const auto [kept, record] = decideByMinimax(volume, box, eps);
    ASSERT_TRUE(kept.accepted);
    EXPECT_FALSE(record.lsq.accepted);
    EXPECT_GT(record.centredHalfRange, eps);
    EXPECT_EQ(record.state, BoxRecord::Minimax::Found);
    EXPECT_LE(worstSample(volume, box, kept), eps);
    EXPECT_GT(worstSample(volume, box, record.lsq), eps);

    const FitResult fit = fitVotSpace(volume, options(eps, 3, FitNorm::Minimax));
    ASSERT_EQ(fit.space.vots.size(), 1u);
    EXPECT_TRUE(verifyVotSpace(fit.space, volume).ok);
    EXPECT_GT(fit.stats.minimaxAccepted, 0u);
}
