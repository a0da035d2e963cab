// Vot MIP of exact polynomial Vot-Spaces: analytic max equals a dense CPU ray sampling, and matches the
// exact grid reference within the trilinear interpolation allowance.
#include "RenderTestSupport.h"

#include "vots/fit/Fitter.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vots;
using namespace vots::render;

namespace {

constexpr int N = 24;
constexpr double AMPLITUDE = 100.0;
constexpr int W = 64, H = 48;

struct Case {
    int degree;
    Projection projection;
    int side; // Vot box side in cells
    VotRenderer::Strategy strategy;
};

class PolynomialMip : public ::testing::TestWithParam<Case> {};

} // namespace

TEST_P(PolynomialMip, AnalyticMaxMatchesDenseCpuSampling) {
    test::glContext();
    const Case k = GetParam();
    const test::Polynomial p =
        test::randomPolynomial(k.degree, N, AMPLITUDE, 1234u + static_cast<unsigned>(k.degree));
    const fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, k.side);
    VotRenderer renderer;
    renderer.setStrategy(k.strategy);
    renderer.upload(space);
    ASSERT_EQ(renderer.mipStrategy(), k.strategy);
    const Camera cam = test::obliqueCamera(k.projection);
    const FloatImage img = renderer.render(cam, W, H);
    const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
    int hits = 0;
    // Boxes are closed and share faces, so a ray grazing an edge may be clipped to a sliver; dense
    // sampling can also miss the true max by a little: 1e-4 of the amplitude (measured 2e-6..1.1e-5).
    const double worst = test::worstDifference(
        img,
        [&](int x, int y) {
            return test::cpuRayMax(m, {N, N, N}, W, H, x, y, p, 4000);
        },
        &hits);
    EXPECT_GT(hits, W * H / 4);
    EXPECT_LT(worst, 1e-4 * AMPLITUDE) << "degree " << k.degree;
    std::cout << "degree " << k.degree << " max |analytic - dense CPU| = " << worst << "\n";
    test::saveForInspection(img, "poly_deg" + std::to_string(k.degree) + "_side" + std::to_string(k.side) +
                                     (k.projection == Projection::Perspective ? "_persp" : "_ortho"));
}

TEST_P(PolynomialMip, MatchesReferenceRayCaster) {
    test::glContext();
    const Case k = GetParam();
    const test::Polynomial p =
        test::randomPolynomial(k.degree, N, AMPLITUDE, 1234u + static_cast<unsigned>(k.degree));
    const fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, k.side);
    const fit::Volume volume = test::sampleVolume({N, N, N}, p);
    VotRenderer vots;
    vots.setStrategy(k.strategy);
    vots.upload(space);
    GridRenderer grid;
    grid.upload(volume);
    const Camera cam = test::obliqueCamera(k.projection);
    const FloatImage a = vots.render(cam, W, H);
    const FloatImage b = grid.render(cam, W, H);
    double worst = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        ASSERT_EQ(std::isfinite(a.pixels[i]), std::isfinite(b.pixels[i])) << i;
        if (std::isfinite(a.pixels[i])) worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
    }
    // The reference is the exact max of the trilinear interpolant of the samples, which differs from the
    // polynomial between samples by at most h^2/8 * sum |f_ii|, about 1 % of the amplitude for these fields.
    EXPECT_LT(worst, 0.02 * AMPLITUDE);
    std::cout << "degree " << k.degree << " max |vot - reference| = " << worst << "\n";
}

constexpr auto WALK = VotRenderer::Strategy::Walk, SPLAT = VotRenderer::Strategy::Splat;
INSTANTIATE_TEST_SUITE_P(
    DegreesAndProjections, PolynomialMip,
    ::testing::Values(Case{2, Projection::Orthographic, 23, WALK},
                      Case{3, Projection::Orthographic, 23, WALK}, Case{3, Projection::Orthographic, 5, WALK},
                      Case{2, Projection::Perspective, 7, WALK}, Case{3, Projection::Perspective, 4, WALK},
                      Case{2, Projection::Orthographic, 23, SPLAT},
                      Case{3, Projection::Orthographic, 5, SPLAT}, Case{2, Projection::Perspective, 7, SPLAT},
                      Case{3, Projection::Perspective, 4, SPLAT}));

TEST(PolynomialMipFitted, FitterOutputMatchesDenseCpuSampling) {
    test::glContext();
    // A degree-3 polynomial is fitted exactly by the fitter (every box reproduces it up to float
    // rounding), so its MIP must equal the polynomial's own ray maxima.
    const test::Polynomial p = test::randomPolynomial(3, N, AMPLITUDE, 77u);
    const fit::Volume volume = test::sampleVolume({N, N, N}, p);
    fit::FitOptions options;
    options.eps = static_cast<float>(1e-3 * AMPLITUDE);
    options.degree = 3;
    const fit::VotSpace space = fit::fitVotSpace(volume, options).space;
    for (const auto strategy : {VotRenderer::Strategy::Walk, VotRenderer::Strategy::Splat}) {
        VotRenderer renderer;
        renderer.setStrategy(strategy);
        renderer.upload(space);
        const Camera cam = test::obliqueCamera(Projection::Perspective);
        const FloatImage img = renderer.render(cam, W, H);
        const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
        double worst = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double expect = test::cpuRayMax(m, {N, N, N}, W, H, x, y, p, 4000);
                if (std::isfinite(expect)) worst = std::max(worst, std::abs(img.at(x, y) - expect));
            }
        EXPECT_LT(worst, options.eps + 1e-4 * AMPLITUDE) << space.vots.size() << " Vots";
    }
}
