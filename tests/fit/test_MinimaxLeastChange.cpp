// The least-change search (white box, fit/src): what it finds is within its target at every point, it finds
// most of what the exchange proves reachable, and nothing the exchange proves out of reach.
#include "BoxFit.h"
#include "Minimax.h"
#include "MinimaxChecks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace vots::fit;
using namespace vots::test;

namespace {

/// The least-squares coefficients of an outcome over the box's scaled coordinates (what decide() starts
/// from): an index-unit coefficient times half-extent^exponent.
std::array<double, MONOMIAL_COUNT> scaledStart(const Box& box, const BoxOutcome& lsq) {
    std::array<double, MONOMIAL_COUNT> scaled{};
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        double factor = 1.0;
        for (int a = 0; a < 3; ++a)
            factor *= std::pow(0.5 * box.cells(a), e[a]);
        scaled[i] = static_cast<double>(lsq.c[i]) * factor;
    }
    return scaled;
}

} // namespace

TEST(Minimax, WhatTheLeastChangeSearchFindsIsWithinItsTargetAtEveryPoint) {
    // Boxes of 8 to 729 samples of a real volume (priced whole, or by scans beyond 256 samples); the target
    // just above or just below the minimax error the exchange converges to. Whatever the search offers is
    // checked here at every point it fits (samples; with cells every point of the half-integer lattice), and
    // it must find most of the boxes whose minimax polynomial is within the target by a margin.
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> corner(0, 40), side(1, 8);
    FitCounters counters;
    int reachable = 0, found = 0, offered = 0, outOfReach = 0, large = 0;
    for (int trial = 0; trial < 240; ++trial) {
        Box box;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = corner(rng) + (a == 2 ? 30 : 10);
            box.hi[a] = box.lo[a] + side(rng);
        }
        if (box.cellCount() == 1) continue;
        const Certify certify = trial % 2 ? Certify::Cells : Certify::Samples;
        const BoxFitter lsqFitter(volume, 3, certify, FitNorm::Lsq);
        const BoxOutcome lsq = lsqFitter.fit(box, EpsField(1e9f), counters);
        const std::uint32_t mask = basisMask(box, 3);
        const auto start = scaledStart(box, lsq);
        const MinimaxSolution minimax = fitMinimax(volume, box, mask, certify, start);
        if (minimax.result != MinimaxSolution::Result::Converged || minimax.maxResidual < 1.0) continue;
        // Every third box gets a target the minimax polynomial cannot reach.
        const bool reachableTarget = trial % 3 != 0;
        const double level = minimax.maxResidual * (reachableTarget ? 1.05 : 0.97);
        MinimaxTarget target;
        target.acceptBelow = level;
        double worstOffered = 0.0;
        target.accept = [&](const std::array<double, MONOMIAL_COUNT>& scaled) {
            ++offered;
            worstOffered = largestLatticeResidual(volume, box, scaled, certify == Certify::Cells);
            return true;
        };
        const MinimaxSolution s = findWithinTarget(volume, box, mask, certify, start, target);
        if (s.result == MinimaxSolution::Result::Found) {
            EXPECT_LE(worstOffered, level * (1.0 + 1e-9)) << "trial " << trial;
            EXPECT_LE(worstOffered, s.maxResidual * (1.0 + 1e-9) + 1e-9) << "trial " << trial;
        } else {
            EXPECT_EQ(s.result, MinimaxSolution::Result::NotFound);
        }
        large += box.pointCount() > MINIMAX_DENSE_POINTS;
        if (reachableTarget) {
            ++reachable;
            found += s.result == MinimaxSolution::Result::Found;
        } else {
            ++outOfReach;
            EXPECT_NE(s.result, MinimaxSolution::Result::Found) << "below the minimax error, trial " << trial;
        }
    }
    EXPECT_GE(outOfReach, 20);
    EXPECT_GE(large, 40);
    EXPECT_GE(reachable, 40);
    EXPECT_GE(found * 10, reachable * 9) << found << " of " << reachable;
    EXPECT_EQ(offered, found);
}
