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

namespace {

/// The polynomial of scaled coefficients at index point (x, y, z) of the box.
double scaledPolynomial(const std::array<double, MONOMIAL_COUNT>& scaled, const Box& box, double x, double y,
                        double z) {
    const double u[3] = {(x - 0.5 * (box.lo[0] + box.hi[0])) / (0.5 * box.cells(0)),
                         (y - 0.5 * (box.lo[1] + box.hi[1])) / (0.5 * box.cells(1)),
                         (z - 0.5 * (box.lo[2] + box.hi[2])) / (0.5 * box.cells(2))};
    double p = 0.0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        p += scaled[i] * std::pow(u[0], e[0]) * std::pow(u[1], e[1]) * std::pow(u[2], e[2]);
    }
    return p;
}

} // namespace

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
        const MinimaxSolution s = fitMinimax(volume, box, mask, certify, start, MinimaxTarget{});
        if (box.cellCount() == 1 || s.result != MinimaxSolution::Result::Converged) continue;
        ++converged;
        EXPECT_LE(s.lowerBound, s.maxResidual * (1.0 + 1e-12));
        EXPECT_LE(s.maxResidual, s.lowerBound * (1.0 + MINIMAX_TOLERANCE) + 1e-6);
        if (certify == Certify::Samples) {
            EXPECT_LE(s.maxResidual, lsq.errSamples * (1.0 + 1e-6) + 1e-6);
        }
        // The reported residual, recomputed from the coefficients over scaled coordinates.
        double worst = 0.0;
        for (int z = box.lo[2]; z <= box.hi[2]; ++z)
            for (int y = box.lo[1]; y <= box.hi[1]; ++y)
                for (int x = box.lo[0]; x <= box.hi[0]; ++x)
                    worst = std::max(worst,
                                     std::abs(scaledPolynomial(s.scaled, box, x, y, z) - volume.at(x, y, z)));
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
            const MinimaxSolution quick = fitMinimax(volume, first, mask, Certify::Cells, start, anything);
            ASSERT_EQ(quick.result, MinimaxSolution::Result::Found);
            afterShortSearch = fitMinimax(volume, box, mask, Certify::Cells, start, MinimaxTarget{});
        }).join();
        std::thread([&] {
            fresh = fitMinimax(volume, box, mask, Certify::Cells, start, MinimaxTarget{});
        }).join();
        EXPECT_EQ(afterShortSearch.result, fresh.result);
        EXPECT_EQ(afterShortSearch.scaled, fresh.scaled);
        if (fresh.result != MinimaxSolution::Result::Converged) continue;
        ++converged;
        double worst = 0.0;
        for (int tz = 2 * box.lo[2]; tz <= 2 * box.hi[2]; ++tz)
            for (int ty = 2 * box.lo[1]; ty <= 2 * box.hi[1]; ++ty)
                for (int tx = 2 * box.lo[0]; tx <= 2 * box.hi[0]; ++tx) {
                    double sum = 0.0;
                    int count = 0;
                    for (int k = 0; k <= (tz & 1); ++k)
                        for (int j = 0; j <= (ty & 1); ++j)
                            for (int i = 0; i <= (tx & 1); ++i, ++count)
                                sum += volume.at(tx / 2 + i, ty / 2 + j, tz / 2 + k);
                    const double p = scaledPolynomial(fresh.scaled, box, 0.5 * tx, 0.5 * ty, 0.5 * tz);
                    worst = std::max(worst, std::abs(p - sum / count));
                }
        EXPECT_LE(worst, fresh.maxResidual * (1.0 + 1e-9) + 1e-9) << "shift " << shift;
    }
    EXPECT_GE(converged, 4);
}
