// Fitting on synthetic fields with known answers: exact polynomials, cell Vots, eps honoured, cache reuse.
#include "SyntheticFields.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace vots::fit;
using vots::test::randomPolynomial;
using vots::test::randomVolume;
using vots::test::sampleVolume;
using vots::test::trilinear;

namespace {

FitOptions options(float eps, int degree, FitMethod method = FitMethod::Fast) {
    FitOptions o;
    o.eps = eps;
    o.degree = degree;
    o.method = method;
    return o;
}

double range(const Volume& v) {
    const auto r = v.valueRange();
    return static_cast<double>(r[1]) - r[0];
}

} // namespace

class PolynomialField : public ::testing::TestWithParam<int> {};

TEST_P(PolynomialField, IsReproducedByOneVotOfTheSameDegree) {
    const int degree = GetParam();
    const std::array<int, 3> dims{14, 11, 9};
    const auto poly = randomPolynomial(degree, dims, 100u + static_cast<unsigned>(degree));
    const Volume volume = sampleVolume(dims, [&](int x, int y, int z) { return poly(x, y, z); });
    const auto r = volume.valueRange();
    const double tolerance = 1e-4 * std::max({range(volume), std::abs(double(r[0])), std::abs(double(r[1]))});
    const FitResult fit = fitVotSpace(volume, options(static_cast<float>(tolerance), degree));
    ASSERT_EQ(fit.space.vots.size(), 1u) << "an exact degree-" << degree << " field needs a single Vot";
    const Vot& vot = fit.space.vots[0];
    EXPECT_EQ(vot.box, (Box{{0, 0, 0}, {13, 10, 8}}));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 500; ++n) {
        const double x = u(rng) * 13, y = u(rng) * 10, z = u(rng) * 8;
        EXPECT_NEAR(vot.evaluate({x, y, z}), poly(x, y, z), tolerance) << "at " << x << "," << y << "," << z;
    }
}

INSTANTIATE_TEST_SUITE_P(Degrees, PolynomialField, ::testing::Values(0, 1, 2, 3));

TEST(CellVot, ReproducesTrilinearAtRandomPoints) {
    const Volume volume = randomVolume({2, 2, 2}, 3u);
    const FitResult fit = fitVotSpace(volume, options(1e-3f, 3));
    ASSERT_EQ(fit.space.vots.size(), 1u);
    const Vot& vot = fit.space.vots[0];
    // docs/DESIGN.md §2 closed form: c = mean, c_x = 1/4 sum s_i f, c_xy = 1/2 sum s_i s_j f, c_xyz = sum s_i
    // s_j s_k f.
    double c0 = 0, cx = 0, cxy = 0, cxyz = 0;
    for (int n = 0; n < 8; ++n) {
        const int i = n & 1, j = (n >> 1) & 1, k = (n >> 2) & 1;
        const double f = volume.at(i, j, k), si = i ? 1 : -1, sj = j ? 1 : -1, sk = k ? 1 : -1;
        c0 += f / 8;
        cx += si * f / 4;
        cxy += si * sj * f / 2;
        cxyz += si * sj * sk * f;
    }
    EXPECT_NEAR(vot.c[0], c0, 1e-3);
    EXPECT_NEAR(vot.c[1], cx, 1e-3);
    EXPECT_NEAR(vot.c[7], cxy, 1e-3);
    EXPECT_NEAR(vot.c[19], cxyz, 1e-3);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n = 0; n < 1000; ++n) {
        const double x = u(rng), y = u(rng), z = u(rng);
        EXPECT_NEAR(vot.evaluate({x, y, z}), trilinear(volume, x, y, z), 1e-3);
    }
}

class LowDegreeCells : public ::testing::TestWithParam<int> {};

TEST_P(LowDegreeCells, FallBackToExactTrilinearCellsWhateverTheDegree) {
    // Random data with a tiny eps: only single cells fit, and they must use the 8-term basis (docs/DESIGN.md
    // §2).
    const Volume volume = randomVolume({5, 4, 4}, 5u);
    const FitResult fit = fitVotSpace(volume, options(1e-3f, GetParam()));
    EXPECT_EQ(fit.space.vots.size(), 4u * 3u * 3u);
    EXPECT_EQ(fit.space.degree, 3) << "header degree is the highest stored degree (xyz terms)";
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const Vot& vot : fit.space.vots) {
        ASSERT_EQ(vot.box.cellCount(), 1);
        for (int n = 0; n < 20; ++n) {
            const double x = vot.box.lo[0] + u(rng), y = vot.box.lo[1] + u(rng), z = vot.box.lo[2] + u(rng);
            EXPECT_NEAR(vot.evaluate({x, y, z}), trilinear(volume, x, y, z), 2e-3);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Degrees, LowDegreeCells, ::testing::Values(0, 1, 2));

class BothMethods : public ::testing::TestWithParam<FitMethod> {};

TEST_P(BothMethods, SmoothNoisyFieldIsCoveredWithinEps) {
    std::mt19937 rng(17);
    std::normal_distribution<double> noise(0.0, 2.0);
    const Volume volume = sampleVolume({30, 26, 20}, [&](int x, int y, int z) {
        return 500.0 * std::sin(0.21 * x) * std::cos(0.17 * y) + 40.0 * z + noise(rng);
    });
    for (int degree : {1, 3}) {
        FitOptions o = options(20.f, degree, GetParam());
        o.background = 0.f; // part of the field is negative: omitted
        const FitResult fit = fitVotSpace(volume, o);
        const VerifyReport report = verifyVotSpace(fit.space, volume);
        EXPECT_TRUE(report.ok) << report.firstProblem;
        EXPECT_EQ(report.uncoveredCells, 0u);
        EXPECT_EQ(report.violations, 0u);
        EXPECT_LE(report.maxError, 20.0 + 1e-2);
        EXPECT_GT(report.nonBackgroundCells, 1000u);
        EXPECT_LT(report.nonBackgroundCells, 29u * 25u * 19u) << "some cells must be background";
        EXPECT_LT(fit.space.vots.size(), report.nonBackgroundCells / 4)
            << "Vots should be much larger than cells";
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, BothMethods, ::testing::Values(FitMethod::Fast, FitMethod::Paper));

TEST(Fitter, FocusRegionGetsItsOwnEps) {
    std::mt19937 rng(19);
    std::normal_distribution<double> noise(0.0, 3.0);
    const Volume volume = sampleVolume({32, 32, 24}, [&](int x, int y, int z) {
        return 200.0 * std::sin(0.3 * x + 0.2 * y) + 5.0 * z + noise(rng);
    });
    FitOptions o = options(30.f, 2);
    o.focus = FocusRegion{{16.0, 16.0, 12.0}, 6.0, 2.f};
    const FitResult focused = fitVotSpace(volume, o);
    const FitResult plain = fitVotSpace(volume, options(30.f, 2));
    EXPECT_TRUE(focused.space.epsVaries);
    const EpsField field(30.f, o.focus);
    const VerifyReport report = verifyVotSpace(focused.space, volume, field);
    EXPECT_TRUE(report.ok) << report.firstProblem;
    // Inside the sphere every sample must be within 2, which the plain fit does not achieve.
    const VerifyReport plainAgainstFocus = verifyVotSpace(plain.space, volume, field);
    EXPECT_GT(plainAgainstFocus.violations, 0u);
    EXPECT_GT(focused.space.vots.size(), plain.space.vots.size());
}

TEST(Fitter, RefitAtNewEpsReusesCacheAndMatchesFreshFit) {
    std::mt19937 rng(23);
    std::normal_distribution<double> noise(0.0, 4.0);
    const Volume volume = sampleVolume({40, 36, 30}, [&](int x, int y, int z) {
        return 300.0 * std::cos(0.15 * x) * std::sin(0.2 * y + 0.1 * z) + noise(rng);
    });
    FitCache cache;
    const FitResult first = fitVotSpace(volume, options(10.f, 3), &cache);
    EXPECT_GT(first.stats.boxFits, 0u);
    const FitResult refit = fitVotSpace(volume, options(25.f, 3), &cache);
    const FitResult fresh = fitVotSpace(volume, options(25.f, 3));
    EXPECT_GT(refit.stats.cacheHits, 0u);
    EXPECT_LT(refit.stats.boxFits * 2, fresh.stats.boxFits) << "most boxes should come from the cache";
    ASSERT_EQ(refit.space.vots.size(), fresh.space.vots.size());
    for (std::size_t i = 0; i < fresh.space.vots.size(); ++i)
        EXPECT_EQ(refit.space.vots[i].box, fresh.space.vots[i].box);
    EXPECT_TRUE(verifyVotSpace(refit.space, volume).ok);
}

TEST(Fitter, CertifyCellsBoundsTheErrorAtCellCentres) {
    // A sharp step: a cubic through 0,0,1,1 overshoots between samples (docs/DESIGN.md §3).
    const Volume volume = sampleVolume({24, 12, 12}, [](int x, int, int) { return x < 12 ? 0.0 : 2000.0; });
    FitOptions o = options(50.f, 3);
    o.certify = Certify::Cells;
    const FitResult fit = fitVotSpace(volume, o);
    const VerifyReport report = verifyVotSpace(fit.space, volume);
    EXPECT_TRUE(report.ok) << report.firstProblem;
    EXPECT_LE(report.maxCellCentreError, 50.0 + 1e-2);
}

TEST(Fitter, BackgroundFillIsTheMeanOfTheTrilinearFieldOverTheOmittedCells) {
    // Three cells along x; the first two have every corner below 10 and are omitted, the third has 100s.
    constexpr double COLUMN[4] = {-8.0, -4.0, -2.0, 100.0};
    const Volume volume = sampleVolume(
        {4, 2, 2}, [&](int x, int y, int z) { return x == 3 ? COLUMN[3] : COLUMN[x] + y + 2 * z; });
    FitOptions o = options(1.f, 3);
    o.background = 10.f;
    const FitResult fit = fitVotSpace(volume, o);
    EXPECT_EQ(fit.stats.backgroundCells, 2u);
    // Each omitted cell's mean is its corners' mean: (-8 - 4) / 2 + 0.5 + 1 and (-4 - 2) / 2 + 0.5 + 1.
    EXPECT_EQ(fit.stats.backgroundValueSum, -4.5 + -1.5);
    ASSERT_TRUE(fit.space.backgroundFill);
    EXPECT_EQ(*fit.space.backgroundFill, -3.f);
    EXPECT_EQ(fit.space.omittedCellValue(), -3.f);
    EXPECT_EQ(fit.space.background, 10.f);

    // Nothing omitted (no threshold, or one below every sample): no fill, and the threshold stands.
    const FitResult none = fitVotSpace(volume, options(1.f, 3));
    EXPECT_FALSE(none.space.backgroundFill);
    o.background = -100.f;
    const FitResult low = fitVotSpace(volume, o);
    EXPECT_EQ(low.stats.backgroundCells, 0u);
    EXPECT_FALSE(low.space.backgroundFill);
    EXPECT_EQ(low.space.omittedCellValue(), -100.f);
}

TEST(Fitter, BackgroundFillAveragesEveryOmittedCellOfARandomVolume) {
    const Volume volume = randomVolume({13, 11, 9}, 41u, -1000.0, 1000.0);
    FitOptions o = options(200.f, 2);
    o.background = 600.f; // random corners: about a quarter of cells have all 8 below
    const FitResult fit = fitVotSpace(volume, o);
    double sum = 0.0;
    std::size_t cells = 0;
    for (int k = 0; k + 1 < 9; ++k)
        for (int j = 0; j + 1 < 11; ++j)
            for (int i = 0; i + 1 < 13; ++i) {
                double corners = 0.0;
                bool omitted = true;
                for (int c = 0; c < 8; ++c) {
                    const float v = volume.at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
                    omitted = omitted && v < 600.f;
                    corners += v;
                }
                if (omitted) sum += corners / 8.0, ++cells;
            }
    ASSERT_GT(cells, 50u);
    EXPECT_EQ(fit.stats.backgroundCells, cells);
    EXPECT_NEAR(fit.stats.backgroundValueSum, sum, 1e-9 * std::abs(sum) + 1e-6);
    ASSERT_TRUE(fit.space.backgroundFill);
    EXPECT_FLOAT_EQ(*fit.space.backgroundFill, static_cast<float>(sum / double(cells)));
    EXPECT_LT(*fit.space.backgroundFill, 600.f);
}

TEST(Fitter, TheFocusOfASlabIsNamedInItsWholeGrid) {
    // Planes 10..23 of a 32x32x24 grid, fitted alone as a rank fits its slab under mpirun.
    const auto field = [](int x, int y, int z) { return 200.0 * std::sin(0.3 * x + 0.2 * y) + 0.4 * z * z; };
    const Volume slab = sampleVolume({32, 32, 14}, [&](int x, int y, int z) { return field(x, y, z + 10); });
    FitOptions inGrid = options(30.f, 2);
    inGrid.partOfGrid = PartOfGrid{10, {32, 32, 24}};
    inGrid.focus = FocusRegion{{16.0, 16.0, 12.0}, 6.0, 2.f};
    FitOptions inSlab = options(30.f, 2);
    inSlab.focus = FocusRegion{{16.0, 16.0, 2.0}, 6.0, 2.f};
    const FitResult a = fitVotSpace(slab, inGrid), b = fitVotSpace(slab, inSlab);
    ASSERT_EQ(a.space.vots.size(), b.space.vots.size());
    for (std::size_t i = 0; i < a.space.vots.size(); ++i)
        ASSERT_EQ(a.space.vots[i].box.lo, b.space.vots[i].box.lo) << "Vot " << i;
    EXPECT_GT(a.space.vots.size(), fitVotSpace(slab, options(30.f, 2)).space.vots.size());
    EXPECT_TRUE(verifyVotSpace(a.space, slab, EpsField(30.f, inSlab.focus)).ok);

    inGrid.focus->centerIndex[2] = 5.0; // in the grid, below the slab: allowed
    EXPECT_NO_THROW(fitVotSpace(slab, inGrid));
    inGrid.focus->centerIndex[2] = 30.0; // beyond the whole grid
    EXPECT_THROW(fitVotSpace(slab, inGrid), InputError);
    inGrid.focus->centerIndex[2] = 12.0;
    inGrid.partOfGrid->firstPlane = 11; // planes 11..24 do not fit in 24
    EXPECT_THROW(fitVotSpace(slab, inGrid), InputError);
}

TEST(Fitter, RejectsAbsurdOptions) {
    const Volume volume = randomVolume({4, 4, 4}, 1u);
    EXPECT_THROW(fitVotSpace(volume, options(0.f, 3)), InputError);
    EXPECT_THROW(fitVotSpace(volume, options(-1.f, 3)), InputError);
    EXPECT_THROW(fitVotSpace(volume, options(std::nanf(""), 3)), InputError);
    EXPECT_THROW(fitVotSpace(volume, options(1.f, 4)), InputError);
    EXPECT_THROW(fitVotSpace(volume, options(1.f, -1)), InputError);
    FitOptions o = options(1.f, 3);
    o.focus = FocusRegion{{100.0, 0.0, 0.0}, 2.0, 0.5f};
    EXPECT_THROW(fitVotSpace(volume, o), InputError);
    const Volume flat = randomVolume({4, 1, 4}, 1u);
    EXPECT_THROW(fitVotSpace(flat, options(1.f, 3)), InputError);
}

TEST(Verify, DetectsWrongCoefficientsAndMissingCover) {
    const Volume volume = randomVolume({10, 10, 10}, 29u, 0.0, 100.0);
    FitResult fit = fitVotSpace(volume, options(60.f, 3));
    ASSERT_TRUE(verifyVotSpace(fit.space, volume).ok);
    VotSpace broken = fit.space;
    broken.vots[0].c[0] += 500.f;
    EXPECT_GT(verifyVotSpace(broken, volume).violations, 0u);
    VotSpace missing = fit.space;
    missing.vots.pop_back();
    const VerifyReport r = verifyVotSpace(missing, volume);
    EXPECT_GT(r.uncoveredCells, 0u);
    EXPECT_FALSE(r.ok);
}
