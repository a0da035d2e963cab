// Minimax fits stay within eps by a recomputation of their own, and cell certification bounds the overshoot.
#include "MinimaxChecks.h"
#include "SyntheticFields.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace vots::fit;
using namespace vots::test;

namespace {

/// The largest |P - trilinear| / eps over every Vot on the lattice of quarter steps: between the points
/// certification tests, where a MIP sees the polynomial too.
double worstOvershoot(const VotSpace& space, const Volume& volume, float eps) {
    double worst = 0.0;
    for (const Vot& vot : space.vots) {
        const Box& b = vot.box;
        for (int zi = 4 * b.lo[2]; zi <= 4 * b.hi[2]; ++zi)
            for (int yi = 4 * b.lo[1]; yi <= 4 * b.hi[1]; ++yi)
                for (int xi = 4 * b.lo[0]; xi <= 4 * b.hi[0]; ++xi) {
                    const double x = 0.25 * xi, y = 0.25 * yi, z = 0.25 * zi;
                    worst = std::max(worst, std::abs(evaluate(vot, x, y, z) - trilinear(volume, x, y, z)));
                }
    }
    return worst / eps;
}

} // namespace

TEST(Minimax, EveryFitStaysWithinEpsAndCoversEveryCellOnce) {
    struct Case {
        const char* file;
        float epsPercent;
        int degree;
        Certify certify;
        bool focus;
    };
    const Case cases[] = {
        {"cranium-quarter_64x64x108_int16.nrrd", 2.f, 3, Certify::Cells, false},
        {"cranium-quarter_64x64x108_int16.nrrd", 1.f, 3, Certify::Samples, true},
        {"blobs_64x64x64_uint8.nrrd", 2.f, 2, Certify::Samples, false},
        {"orbital_64x64x64_float32.nrrd", 1.f, 3, Certify::Cells, false},
        {"mri-brain_33x41x25_int16.nrrd", 5.f, 1, Certify::Cells, true},
        {"mri-brain_33x41x25_int16.nrrd", 2.f, 0, Certify::Samples, false},
    };
    for (const Case& c : cases) {
        const Volume volume = loadShared(c.file);
        const auto range = volume.valueRange();
        FitOptions o =
            options(c.epsPercent / 100.f * (range[1] - range[0]), c.degree, FitNorm::Minimax, c.certify);
        o.background = defaultBackground(volume);
        if (c.focus) {
            o.focus = FocusRegion{{0.5 * volume.dims[0], 0.5 * volume.dims[1], 0.5 * volume.dims[2]},
                                  0.2 * volume.dims[0],
                                  0.25f * o.eps};
        }
        const std::string what = std::string(c.file) + " at " + std::to_string(c.epsPercent) + " %, degree " +
                                 std::to_string(c.degree);
        const FitResult fit = fitVotSpace(volume, o);
        const EpsField field(o.eps, o.focus);
        const VerifyReport report = verifyVotSpace(fit.space, volume, field);
        EXPECT_TRUE(report.ok) << what << ": " << report.firstProblem;
        const Independent check =
            recompute(fit.space, volume, field, *o.background, c.certify == Certify::Cells);
        EXPECT_EQ(check.beyondEps, 0u) << what;
        EXPECT_EQ(check.uncovered, 0u) << what;
        EXPECT_EQ(check.doublyCovered, 0u) << what;
        EXPECT_GT(check.samples, 0u) << what;
        if (c.certify == Certify::Cells) {
            EXPECT_LE(check.worstCellPoint, 1.0 + 1e-5) << what;
        }
        const FitResult lsq = fitVotSpace(volume, [&] {
            FitOptions l = o;
            l.norm = FitNorm::Lsq;
            return l;
        }());
        EXPECT_LE(fit.space.vots.size(), lsq.space.vots.size()) << what;
    }
}

TEST(Minimax, CellCertificationStillBoundsTheOvershoot) {
    // Certified points are within eps (the fit above); between them a polynomial overshoots what it holds
    // at them. Minimax polynomials sit near eps at many points where least squares' stay inside, so at the
    // cells they are held to MINIMAX_CELLS_TARGET eps, face centres included: their overshoot on a lattice
    // four times finer than the samples' is no worse than least squares'.
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    const auto range = volume.valueRange();
    const float eps = 0.02f * (range[1] - range[0]);
    FitOptions o = options(eps, 3, FitNorm::Minimax, Certify::Cells);
    o.background = defaultBackground(volume);
    const FitResult minimax = fitVotSpace(volume, o);
    o.norm = FitNorm::Lsq;
    const FitResult lsq = fitVotSpace(volume, o);
    EXPECT_LT(minimax.space.vots.size(), lsq.space.vots.size());
    const double worstMinimax = worstOvershoot(minimax.space, volume, eps);
    const double worstLsq = worstOvershoot(lsq.space, volume, eps);
    EXPECT_LE(worstMinimax, worstLsq + 0.02) << "least squares: " << worstLsq;
    EXPECT_LT(worstMinimax, 1.6);
}

TEST(Minimax, EveryDegreeFitsWithinEpsInFewerOrAsManyVots) {
    const Volume volume = loadShared("cranium-quarter_64x64x108_int16.nrrd");
    const auto range = volume.valueRange();
    for (int degree = 0; degree <= 3; ++degree) {
        FitOptions o = options(0.02f * (range[1] - range[0]), degree, FitNorm::Minimax);
        o.background = defaultBackground(volume);
        const FitResult minimax = fitVotSpace(volume, o);
        o.norm = FitNorm::Lsq;
        const FitResult lsq = fitVotSpace(volume, o);
        EXPECT_TRUE(verifyVotSpace(minimax.space, volume).ok) << "degree " << degree;
        EXPECT_LE(minimax.space.vots.size(), lsq.space.vots.size()) << "degree " << degree;
        if (degree == 3) {
            EXPECT_LT(minimax.space.vots.size(), lsq.space.vots.size() * 9 / 10);
        }
    }
}
