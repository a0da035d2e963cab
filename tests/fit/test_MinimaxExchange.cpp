// The minimax exchange (white box, fit/src): it reaches the minimax polynomial, whatever its shape cache
// held.
#include "BoxFit.h"
#include "Minimax.h"
#include "MinimaxChecks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <thread>

using namespace vots::fit;
using namespace vots::test;

TEST(Minimax, TheExchangeReachesTheMinimaxPolynomial) {
    // On boxes of a real volume: where it converges, the polynomial's largest residual is within the
    // tolerance of the lower bound the dual LP proves, never above least squares', and what it reports.
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> corner(0, 40), side(1, 9);
    FitCounters counters;
    int converged = 0;
    for (int trial = 0; trial < 120; ++trial) {
        Box box;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = corner(rng) + (a == 2 ? 30 : 10);
            box.hi[a] = box.lo[a] + side(rng);
        }
        const Certify certify = trial % 2 ? Certify::Cells : Certify::Samples;
        const BoxFitter lsqFitter(volume, 3, certify, FitNorm::Lsq);
        const BoxOutcome lsq = lsqFitter.fit(box, EpsField(1e9f), counters); // certified: its exact error
        const std::uint32_t mask = basisMask(box, 3);
        std::array<double, MONOMIAL_COUNT> start{};
        const MinimaxSolution s = fitMinimax(volume, box, mask, certify, start);
        if (box.cellCount() == 1 || s.result != MinimaxSolution::Result::Converged) continue;
        ++converged;
        EXPECT_LE(s.lowerBound, s.maxResidual * (1.0 + 1e-12));
        EXPECT_LE(s.maxResidual, s.lowerBound * (1.0 + MINIMAX_TOLERANCE) + 1e-6);
        if (certify == Certify::Samples) {
            EXPECT_LE(s.maxResidual, lsq.errSamples * (1.0 + 1e-6) + 1e-6);
        }
        // The reported residual, recomputed from the coefficients over scaled coordinates.
        const double worst = largestLatticeResidual(volume, box, s.scaled, false);
        EXPECT_LE(worst, s.maxResidual * (1.0 + 1e-9) + 1e-9);
    }
    EXPECT_GT(converged, 60);
}

TEST(Minimax, ACellsSearchHoldsEveryCellPointWhateverTheShapeCacheHeld) {
    // A search that ends before it prices the cell points leaves its box shape's cell rows unfilled in the
    // thread's cache; a later search of the same shape that needs them must see their true values. Each
    // converged cells search holds every point of the half-integer lattice (samples, edge midpoints, face
    // and cell centres at their trilinear value) within its reported residual, and gives the polynomial it
    // gives on a thread whose cache is empty.
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    const Box first{{10, 12, 40}, {14, 15, 43}};
    MinimaxTarget anything;
    anything.acceptBelow = 1e30;
    anything.accept = [](const std::array<double, MONOMIAL_COUNT>&) { return true; };
    int converged = 0;
    for (int shift = 0; shift < 6; ++shift) {
        Box box = first;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] += 4 * shift + a;
            box.hi[a] += 4 * shift + a;
        }
        const std::uint32_t mask = basisMask(box, 3);
        const std::array<double, MONOMIAL_COUNT> start{};
        MinimaxSolution afterShortSearch, fresh;
        std::thread([&] {
            const MinimaxSolution quick =
                findWithinTarget(volume, first, mask, Certify::Cells, start, anything);
            ASSERT_EQ(quick.result, MinimaxSolution::Result::Found);
            afterShortSearch = fitMinimax(volume, box, mask, Certify::Cells, start);
        }).join();
        std::thread([&] { fresh = fitMinimax(volume, box, mask, Certify::Cells, start); }).join();
        EXPECT_EQ(afterShortSearch.result, fresh.result);
        EXPECT_EQ(afterShortSearch.scaled, fresh.scaled);
        if (fresh.result != MinimaxSolution::Result::Converged) continue;
        ++converged;
        const double worst = largestLatticeResidual(volume, box, fresh.scaled, true);
        EXPECT_LE(worst, fresh.maxResidual * (1.0 + 1e-9) + 1e-9) << "shift " << shift;
    }
    EXPECT_GE(converged, 4);
}
