// MinIP, average and thick-slab projections of exact polynomial Vot-Spaces against a dense CPU oracle,
// with background cells, culling, the slab planes, and the cases the Vot renderer refuses.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/Slab.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <optional>
#include <vector>

using namespace vots;
using namespace vots::render;

namespace {

constexpr int N = 24;
constexpr double AMPLITUDE = 100.0;
constexpr int W = 64, H = 48;
constexpr int SAMPLES = 4000;

// The CPU oracle's profile of every pixel's ray (slab: only the part of the ray inside it).
std::vector<test::RayProfile> oracleProfiles(const CameraMatrices& m, const test::Polynomial& p,
                                             const std::optional<SlabPlanes>& slab = std::nullopt) {
    std::vector<test::RayProfile> oracle(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            oracle[y * W + x] = test::cpuRayProfile(m, {N, N, N}, W, H, x, y, p, SAMPLES, slab);
    return oracle;
}

struct Case {
    int degree;
    Projection projection;
};

class PolynomialProjections : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(PolynomialProjections, MinAndMeanMatchDenseCpuProfile) {
    test::glContext();
    const Case k = GetParam();
    const test::Polynomial p =
        test::randomPolynomial(k.degree, N, AMPLITUDE, 777u + static_cast<unsigned>(k.degree));
    VotRenderer renderer;
    renderer.upload(test::polynomialVotSpace(p, {N, N, N}, 4));
    const Camera cam = test::obliqueCamera(k.projection);
    const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
    const FloatImage minImage = renderer.render(cam, W, H, RenderMode::MinIp);
    const FloatImage meanImage = renderer.render(cam, W, H, RenderMode::Aip);
    const FloatImage maxImage = renderer.render(cam, W, H, RenderMode::Mip);
    const std::vector<test::RayProfile> oracle = oracleProfiles(m, p);
    int hits = 0;
    const double minWorst = test::worstDifference(
        minImage, [&](int x, int y) { return oracle[y * W + x].min; }, &hits);
    EXPECT_GT(hits, W * H / 4);
    const double meanWorst = test::worstDifference(
        meanImage, [&](int x, int y) { return oracle[y * W + x].mean; }, &hits);
    // The min as exact as the max (PolynomialMip: dense sampling misses extrema by ~1e-5 of the
    // amplitude); the mean sums float integrals of up to ~20 Vots along a ray (measured 5e-6).
    EXPECT_LT(minWorst, 1e-4 * AMPLITUDE) << "degree " << k.degree;
    EXPECT_LT(meanWorst, 5e-5 * AMPLITUDE) << "degree " << k.degree;
    std::cout << "degree " << k.degree << ": worst |minip - CPU| = " << minWorst
              << ", |aip - CPU| = " << meanWorst << "\n";
    for (std::size_t i = 0; i < minImage.pixels.size(); ++i) {
        if (!std::isfinite(maxImage.pixels[i])) continue;
        const float slack = 1e-4f * float(AMPLITUDE);
        EXPECT_LE(minImage.pixels[i], meanImage.pixels[i] + slack) << i;
        EXPECT_LE(meanImage.pixels[i], maxImage.pixels[i] + slack) << i;
    }
}

TEST_P(PolynomialProjections, EveryModeHonoursTheSlabPlanes) {
    test::glContext();
    const Case k = GetParam();
    const test::Polynomial p =
        test::randomPolynomial(k.degree, N, AMPLITUDE, 991u + static_cast<unsigned>(k.degree));
    VotRenderer renderer;
    renderer.upload(test::polynomialVotSpace(p, {N, N, N}, 4));
    const Camera cam = test::obliqueCamera(k.projection);
    const Slab slab{2.5, 6.0}; // mm; the spacing is 1, so index units
    const SlabPlanes planes = slabPlanesInIndexSpace(slab, cam, renderer.bounds());
    const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
    const std::vector<test::RayProfile> oracle = oracleProfiles(m, p, planes);
    int hits = 0;
    const auto check = [&](RenderMode mode, auto pick, double tolerance) {
        const FloatImage image = renderer.render(cam, W, H, RenderOptions{mode, slab});
        const double worst = test::worstDifference(
            image, [&](int x, int y) { return pick(oracle[y * W + x]); }, &hits);
        EXPECT_GT(hits, W * H / 8) << renderModeName(mode);
        EXPECT_LT(worst, tolerance) << renderModeName(mode) << " degree " << k.degree;
    };
    check(
        RenderMode::Mip, [](const test::RayProfile& r) { return r.max; }, 1e-4 * AMPLITUDE);
    check(
        RenderMode::MinIp, [](const test::RayProfile& r) { return r.min; }, 1e-4 * AMPLITUDE);
    check(
        RenderMode::Aip, [](const test::RayProfile& r) { return r.mean; }, 5e-5 * AMPLITUDE);
    // The raster strategy clips its MIP to the same planes.
    renderer.setStrategy(VotRenderer::Strategy::Raster);
    check(
        RenderMode::Mip, [](const test::RayProfile& r) { return r.max; }, 1e-4 * AMPLITUDE);
}

INSTANTIATE_TEST_SUITE_P(Degrees, PolynomialProjections,
                         ::testing::Values(Case{1, Projection::Orthographic},
                                           Case{2, Projection::Orthographic},
                                           Case{3, Projection::Orthographic},
                                           Case{3, Projection::Perspective}));

TEST(VotProjections, ASlabThickerThanTheVolumeChangesNoPixel) {
    test::glContext();
    const test::Polynomial p = test::randomPolynomial(3, N, AMPLITUDE, 5u);
    VotRenderer renderer;
    renderer.upload(test::polynomialVotSpace(p, {N, N, N}, 4));
    const Camera cam = test::obliqueCamera(Projection::Orthographic);
    for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip}) {
        const FloatImage whole = renderer.render(cam, W, H, mode);
        const FloatImage slabbed = renderer.render(cam, W, H, RenderOptions{mode, Slab{0.0, 1000.0}});
        const test::ImageComparison c = test::compareImages(whole, slabbed, 0.0);
        EXPECT_EQ(c.bitIdentical, whole.pixels.size()) << renderModeName(mode);
    }
}

TEST(VotProjections, BackgroundCellsCountAsTheFillOrWithoutOneTheBackgroundValue) {
    test::glContext();
    const test::Polynomial p = test::randomPolynomial(2, N, AMPLITUDE, 31u);
    fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 4);
    // A hole of 8^3 cells, [8, 16] in index units, that the fit "left out" as background.
    constexpr float BACKGROUND = -10.f * float(AMPLITUDE);
    std::erase_if(space.vots, [](const fit::Vot& v) {
        for (int a = 0; a < 3; ++a)
            if (v.box.lo[a] < 8 || v.box.hi[a] > 16) return false;
        return true;
    });
    space.background = BACKGROUND;
    const auto inHole = [](double x, double y, double z) {
        return x > 8 && x < 16 && y > 8 && y < 16 && z > 8 && z < 16;
    };
    const Camera cam = test::obliqueCamera(Projection::Orthographic);
    // Without a fill (a file from before it) the hole is the threshold; with one, the fill, which sits
    // further below the field than the threshold does: the two images differ wherever a ray crosses it.
    std::vector<FloatImage> minImages;
    for (const std::optional<float> fill :
         {std::optional<float>{}, std::optional<float>{1.5f * BACKGROUND}}) {
        space.backgroundFill = fill;
        const float holeValue = fill.value_or(BACKGROUND);
        const auto field = [&](double x, double y, double z) {
            return inHole(x, y, z) ? holeValue : p(x, y, z);
        };
        VotRenderer renderer;
        renderer.upload(space);
        const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
        const FloatImage minImage = renderer.render(cam, W, H, RenderMode::MinIp);
        const FloatImage meanImage = renderer.render(cam, W, H, RenderMode::Aip);
        int throughHole = 0, hits = 0;
        std::vector<test::RayProfile> oracle(W * H);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                oracle[y * W + x] = test::cpuRayProfile(m, {N, N, N}, W, H, x, y, field, 20000);
                if (oracle[y * W + x].min == holeValue) ++throughHole;
            }
        EXPECT_GT(throughHole, 50);
        EXPECT_LT(test::worstDifference(
                      minImage, [&](int x, int y) { return oracle[y * W + x].min; }, &hits),
                  1e-4 * AMPLITUDE)
            << holeValue;
        // Simpson's rule across the hole's faces, where the field jumps by ~11 amplitudes (~16 with the
        // fill), errs by about jump x step / path length.
        EXPECT_LT(test::worstDifference(
                      meanImage, [&](int x, int y) { return oracle[y * W + x].mean; }, &hits),
                  5e-3 * AMPLITUDE * (holeValue / BACKGROUND))
            << holeValue;
        minImages.push_back(minImage);
    }
    const test::ImageComparison c = test::compareImages(minImages[0], minImages[1], 0.0);
    EXPECT_LT(c.bitIdentical, minImages[0].pixels.size()) << "the fill must change the rays through the hole";
}

TEST(VotProjections, CullingNeverChangesTheMinIp) {
    test::glContext();
    const test::Polynomial p = test::randomPolynomial(3, N, AMPLITUDE, 77u);
    fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 2, 0.3f);
    std::erase_if(space.vots, [](const fit::Vot& v) { return v.box.lo[0] >= 10 && v.box.lo[0] < 14; });
    space.background = -2.f * float(AMPLITUDE);
    VotRenderer renderer;
    renderer.upload(space);
    for (Projection projection : {Projection::Orthographic, Projection::Perspective}) {
        const Camera cam = test::obliqueCamera(projection);
        renderer.setCulling(true);
        const FloatImage culled = renderer.render(cam, W, H, RenderMode::MinIp);
        renderer.finishPendingWork(); // skip boxes grown for the max must not reach the min
        const FloatImage culledLater = renderer.render(cam, W, H, RenderMode::MinIp);
        renderer.setCulling(false);
        const FloatImage everything = renderer.render(cam, W, H, RenderMode::MinIp);
        EXPECT_EQ(test::compareImages(culled, everything, 0.0).bitIdentical, everything.pixels.size());
        EXPECT_EQ(test::compareImages(culledLater, everything, 0.0).bitIdentical, everything.pixels.size());
    }
}

TEST(VotProjections, RefusesWhatItCannotDrawExactly) {
    test::glContext();
    const test::Polynomial p = test::randomPolynomial(1, 8, AMPLITUDE, 3u);
    fit::VotSpace space = test::polynomialVotSpace(p, {8, 8, 8}, 4);
    VotRenderer renderer;
    renderer.setStrategy(VotRenderer::Strategy::Walk); // what the walk cannot draw
    renderer.upload(space);
    EXPECT_THROW(renderer.render(Camera{}, 16, 16, RenderOptions{RenderMode::Density, Slab{0, 4}}),
                 fit::InputError);
    space.vots.push_back(space.vots.front()); // overlapping boxes: only the raster strategy draws them
    renderer.upload(space);
    EXPECT_EQ(renderer.mipStrategy(), VotRenderer::Strategy::Raster);
    EXPECT_THROW(renderer.render(Camera{}, 16, 16, RenderMode::MinIp), fit::InputError);
    EXPECT_THROW(renderer.render(Camera{}, 16, 16, RenderMode::Aip), fit::InputError);
    EXPECT_NO_THROW(renderer.render(Camera{}, 16, 16, RenderOptions{RenderMode::Mip, Slab{0, 4}}));
}

TEST(VotProjections, SlabTextIsTwoFiniteNumbersWithPositiveThickness) {
    EXPECT_EQ(parseSlab("-12.5,30"), (Slab{-12.5, 30}));
    for (const char* bad : {"", "1", "1,", ",2", "1,0", "1,-2", "nan,2", "1,inf", "1,2,3", "1 ,2", "a,b"})
        EXPECT_THROW(parseSlab(bad), fit::InputError) << bad;
    EXPECT_EQ(parseSlab(formatSlab(Slab{0.1, 1.0 / 3.0})), (Slab{0.1, 1.0 / 3.0}));
}
