// Whole-image properties: aspect ratio of anisotropic grids, camera inside the volume, every colormap and
// mode non-blank, byte-identical repeats, and the GPU display pass equal to its CPU statement.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"
#include "vots/render/Colormap.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <vector>

using namespace vots;
using namespace vots::render;

namespace {

// Non-background pixel bounding box: {x0, y0, x1, y1}.
std::array<int, 4> footprint(const FloatImage& img) {
    std::array<int, 4> r{img.width, img.height, -1, -1};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (std::isfinite(img.at(x, y)))
                r = {std::min(r[0], x), std::min(r[1], y), std::max(r[2], x), std::max(r[3], y)};
    return r;
}

std::size_t distinctColours(const RgbaImage& img) {
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i < img.pixels.size(); i += 4)
        colours.insert(img.pixels[i] | img.pixels[i + 1] << 8 | img.pixels[i + 2] << 16);
    return colours.size();
}

} // namespace

TEST(Images, AnisotropicSpacingKeepsProportions) {
    test::glContext();
    // 33 x 33 x 33 points with spacing 0.957 x 0.957 x 1.5 mm: world box 30.6 x 30.6 x 48 mm.
    test::Polynomial constant;
    constant.c[0] = 100.f;
    fit::VotSpace space = test::polynomialVotSpace(constant, {33, 33, 33}, 8);
    space.spacing = {0.957, 0.957, 1.5};
    VotRenderer renderer;
    renderer.upload(space);
    const FloatImage img =
        renderer.render(cameraForView(ViewPreset::Anterior), 300, 300); // image x = world x, y = z
    const auto r = footprint(img);
    const double w = r[2] - r[0] + 1, h = r[3] - r[1] + 1;
    EXPECT_NEAR(w / h, 0.957 / 1.5, 0.02) << w << " x " << h;
    const FloatImage side = renderer.render(cameraForView(ViewPreset::Left), 300, 300); // image x = world y
    const auto s = footprint(side);
    EXPECT_NEAR(double(s[2] - s[0] + 1) / double(s[3] - s[1] + 1), 0.957 / 1.5, 0.02);
    const FloatImage top = renderer.render(cameraForView(ViewPreset::Superior), 300, 300); // x and y
    const auto t = footprint(top);
    EXPECT_NEAR(double(t[2] - t[0] + 1) / double(t[3] - t[1] + 1), 1.0, 0.02);
    test::saveForInspection(img, "aniso_anterior");
}

TEST(Images, CameraInsideTheVolumeStillRenders) {
    test::glContext();
    constexpr int N = 24, W = 48, H = 40;
    const test::Polynomial p = test::randomPolynomial(3, N, 100.0, 99u);
    const fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 6);
    VotRenderer renderer;
    renderer.upload(space);
    const Camera cam = parseCamera("az=20,el=10,zoom=8,proj=persp,fov=60"); // eye 0.24 R from the centre
    const FloatImage img = renderer.render(cam, W, H);
    const CameraMatrices m = computeCameraMatrices(cam, renderer.bounds(), W, H);
    int finite = 0;
    double worst = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double expect = test::cpuRayMax(m, {N, N, N}, W, H, x, y, p, 4000);
            ASSERT_TRUE(std::isfinite(img.at(x, y))) << x << "," << y;
            ++finite;
            worst = std::max(worst, std::abs(img.at(x, y) - expect));
        }
    EXPECT_EQ(finite, W * H);
    // 1e-3 of the amplitude: the near plane sits 1e-3 R from the eye, and float unprojection of it
    // moves the clipped entry point by ~1e-3 voxel (measured worst 0.079 of amplitude 100).
    EXPECT_LT(worst, 0.1);
    test::saveForInspection(img, "inside_persp");
}

TEST(Images, EveryColormapAndModeIsNonBlank) {
    test::glContext();
    constexpr int N = 24;
    const test::Polynomial p = test::randomPolynomial(3, N, 100.0, 5u);
    const fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 3);
    const fit::Volume volume = test::sampleVolume({N, N, N}, p);
    VotRenderer vots;
    vots.upload(space);
    GridRenderer grid;
    grid.upload(volume);
    const Camera cam = parseCamera("az=30,el=20");
    const auto range = vots.valueRange();
    const auto density = vots.densityRange();
    // Made here too: on a fresh machine this test can run before any saveForInspection made it.
    std::filesystem::create_directories("/tmp/vots_render_tests");
    for (Colormap map : ALL_COLORMAPS) {
        const std::string name(colormapName(map));
        const RgbaImage mip = vots.renderRgba(cam, 96, 96, windowForRange(range[0], range[1], map));
        EXPECT_GT(distinctColours(mip), 20u) << name;
        const RgbaImage ref = grid.renderRgba(cam, 96, 96, windowForRange(range[0], range[1], map));
        EXPECT_GT(distinctColours(ref), 20u) << name;
        const RgbaImage den = vots.renderRgba(cam, 96, 96, windowForRange(density[0], density[1] + 1, map),
                                              RenderMode::Density);
        EXPECT_GT(distinctColours(den), 2u) << name;
        writePng("/tmp/vots_render_tests/colormap_" + name + ".png", mip);
        writePng("/tmp/vots_render_tests/density_" + name + ".png", den);
    }
}

TEST(Images, SameCameraGivesByteIdenticalPng) {
    test::glContext();
    constexpr int N = 20;
    const test::Polynomial p = test::randomPolynomial(3, N, 50.0, 11u);
    const fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 2);
    const Camera cam = parseCamera("az=-12.5,el=33,zoom=1.2,pan=0.1:0,proj=persp,fov=35");
    const DisplaySettings display = windowForRange(-50, 50, Colormap::Viridis);
    VotRenderer a;
    a.upload(space);
    const auto first = encodePng(a.renderRgba(cam, 128, 96, display));
    (void)a.render(parseCamera("left"), 64, 64); // something else in between
    const auto second = encodePng(a.renderRgba(cam, 128, 96, display));
    VotRenderer b;
    b.upload(space);
    const auto third = encodePng(b.renderRgba(cam, 128, 96, display));
    EXPECT_EQ(first, second);
    EXPECT_EQ(first, third);
}

TEST(Images, DisplayPassMapsTheWindowOntoTheColourTable) {
    // No GL context: the display pass is the CPU's. Row y holds the 256 window steps k (value low +
    // width * k / 255, which must show entry k) shifted by a third of a step, which rounds to the same
    // entry; the last row is below, above and off the window (entries 0, 255, and 0 for non-finite).
    const DisplaySettings window = parseWindow("300,1000"); // low -200, high 800
    FloatImage img;
    img.width = 256;
    img.height = 3;
    for (int y = 0; y < 2; ++y)
        for (int k = 0; k < 256; ++k)
            img.pixels.push_back(window.low() + window.width * (k + (y == 1 ? 1.f / 3 : 0.f)) / 255.f);
    const std::vector<float> outside{-1e6f, -200.5f, 800.5f, 1e6f, -INFINITY, INFINITY, NAN};
    const std::vector<int> expected{0, 0, 255, 255, 0, 0, 0};
    img.pixels.insert(img.pixels.end(), outside.begin(), outside.end());
    img.pixels.resize(256 * 3, NAN);
    for (Colormap map : ALL_COLORMAPS) {
        DisplaySettings s = window;
        s.colormap = map;
        const RgbaImage out = applyDisplay(img, s);
        ASSERT_EQ(out.width, 256);
        ASSERT_EQ(out.height, 3);
        const ColormapTable& table = colormapTable(map);
        const auto shows = [&](int x, int y, int entry) {
            const std::uint8_t* got = out.at(x, y);
            return std::equal(got, got + 4, table[static_cast<std::size_t>(entry)].begin());
        };
        int mismatches = 0;
        for (int y = 0; y < 2; ++y)
            for (int k = 0; k < 256; ++k)
                mismatches += shows(k, y, k) ? 0 : 1;
        for (std::size_t i = 0; i < outside.size(); ++i)
            mismatches += shows(static_cast<int>(i), 2, expected[i]) ? 0 : 1;
        EXPECT_EQ(mismatches, 0) << colormapName(map);
        EXPECT_EQ(out.at(0, 0)[3], 255) << "opaque";
    }
    FloatImage wrong = img;
    wrong.pixels.pop_back();
    EXPECT_THROW(applyDisplay(wrong, window), fit::GraphicsError);
}

TEST(Images, RejectsBadSizes) {
    test::glContext();
    test::Polynomial constant;
    constant.c[0] = 1.f;
    VotRenderer r;
    r.upload(test::polynomialVotSpace(constant, {4, 4, 4}, 3));
    EXPECT_THROW(r.render(Camera{}, 0, 10), fit::InputError);
    EXPECT_THROW(r.render(Camera{}, 10, 8193), fit::InputError);
    EXPECT_THROW(parseColormap("jet"), fit::InputError);
    EXPECT_THROW(parseModeName("max"), fit::InputError);
    EXPECT_THROW(parseRendererName("gpu"), fit::InputError);
}
