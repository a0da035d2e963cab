// The Splat MIP strategy (the CPU's cores, object order) against Raster and the walk on a fitted real CT.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"
#include "vots/render/Renderer.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vots;
using namespace vots::render;

namespace {

using Strategy = VotRenderer::Strategy;

// Front, oblique, perspective, perspective with the eye inside the volume, and a slab.
constexpr const char* VIEWS[] = {"anterior", "az=30,el=20,zoom=1.2",
                                 "az=-50,el=-30,zoom=1.4,proj=persp,fov=40",
                                 "az=20,el=10,zoom=8,proj=persp,fov=60"};

const test::FittedVolume& head() {
    static const test::FittedVolume fitted =
        test::fitForImages(std::string(VOTS_TEST_DATA_DIR) + "/cranium-quarter_64x64x108_int16.nrrd", 0.02f);
    return fitted;
}

} // namespace

TEST(CpuSplat, IsTheMipStrategyWhereTheContextIsACpuRasteriser) {
    const EglContext& context = test::glContext();
    VotRenderer renderer;
    EXPECT_EQ(renderer.strategy(), context.isSoftware() ? Strategy::Splat : Strategy::Walk)
        << context.renderer();
}

TEST(CpuSplat, MatchesRasterAndTheWalkOnFittedCt) {
    test::glContext();
    const test::FittedVolume& f = head();
    VotRenderer splat, raster, walk;
    splat.setStrategy(Strategy::Splat);
    raster.setStrategy(Strategy::Raster);
    walk.setStrategy(Strategy::Walk);
    for (VotRenderer* r : {&splat, &raster, &walk})
        r->upload(f.space);
    ASSERT_EQ(splat.mipStrategy(), Strategy::Splat);
    const auto range = splat.valueRange();
    for (const char* text : VIEWS)
        for (const std::optional<Slab>& slab :
             {std::optional<Slab>{}, std::optional<Slab>{Slab{-10.0, 25.0}}}) {
            const Camera cam = parseCamera(text);
            const RenderOptions options{RenderMode::Mip, slab};
            const FloatImage a = splat.render(cam, 203, 157, options);
            // Raster evaluates the same float polynomials with the same analytic max: beyond float
            // rounding (1e-5 of the range) they may differ only where a ray grazes a face shared by two
            // boxes (within 5e-5 voxel), where Raster takes both Vots and the splat too.
            const test::ImageComparison toRaster =
                test::compareImages(a, raster.render(cam, 203, 157, options), 1e-5 * (range[1] - range[0]));
            EXPECT_LE(toRaster.finiteMismatch + toRaster.beyondTolerance, a.pixels.size() / 1000) << text;
            EXPECT_LE(toRaster.worst, 2.0 * f.eps) << text;
            // The walk takes one Vot where a ray grazes a shared face and evaluates 16-bit records
            // (WalkRecord.h); both stay within eps of the data, so within 2 eps of each other.
            const test::ImageComparison toWalk =
                test::compareImages(a, walk.render(cam, 203, 157, options), 1e-3 * (range[1] - range[0]));
            EXPECT_LE(toWalk.finiteMismatch + toWalk.beyondTolerance, a.pixels.size() / 500) << text;
            EXPECT_LE(toWalk.worst, 2.0 * f.eps) << text;
            std::size_t hits = 0;
            for (float v : a.pixels)
                hits += std::isfinite(v) ? 1 : 0;
            EXPECT_GT(hits, a.pixels.size() / 10) << text << (slab ? ", slab" : "");
        }
}

TEST(CpuSplat, DrawsOverlappingBoxesAsRasterDoes) {
    test::glContext();
    constexpr int N = 12;
    fit::VotSpace space = test::polynomialVotSpace(test::randomPolynomial(3, N, 100.0, 3u), {N, N, N}, 4);
    space.vots.push_back(space.vots.front()); // the same box twice: the walk cannot take it
    VotRenderer splat, raster;
    splat.setStrategy(Strategy::Splat);
    raster.setStrategy(Strategy::Raster);
    splat.upload(space);
    raster.upload(space);
    EXPECT_EQ(splat.mipStrategy(), Strategy::Splat);
    const Camera cam = parseCamera("az=30,el=20");
    const test::ImageComparison c =
        test::compareImages(splat.render(cam, 64, 48), raster.render(cam, 64, 48), 1e-3);
    EXPECT_EQ(c.finiteMismatch + c.beyondTolerance, 0u) << "worst " << c.worst;
    EXPECT_GT(c.bitIdentical, 0u);
}

TEST(CpuSplat, EmptySpaceAndAnEmptyDomainRenderBackground) {
    test::glContext();
    fit::VotSpace space;
    space.dims = {10, 12, 14};
    VotRenderer renderer;
    renderer.setStrategy(Strategy::Splat);
    renderer.upload(space);
    for (float v : renderer.render(parseCamera("az=30,el=20"), 32, 32).pixels)
        ASSERT_EQ(v, -INFINITY);
    renderer.upload(head().space);
    renderer.setRayDomain(CellDomain{{0, 0, 40}, {63, 63, 40}});
    for (float v : renderer.render(parseCamera("az=30,el=20"), 32, 32).pixels)
        ASSERT_EQ(v, -INFINITY);
}

TEST(CpuSplat, AFrameIsGivenUpWhenAskedAndTheNextIsWhole) {
    test::glContext();
    VotRenderer renderer;
    renderer.setStrategy(Strategy::Splat);
    renderer.upload(head().space);
    const Camera cam = parseCamera("az=-20,el=15,zoom=1.3");
    const FloatImage whole = renderer.render(cam, 120, 90);
    int asked = 0;
    RenderOptions options;
    options.abandoned = [&asked] { return ++asked >= 1; };
    EXPECT_THROW(renderer.render(cam, 120, 90, options), FrameAbandoned);
    EXPECT_EQ(asked, 1); // the first look gives it up: nothing more is asked
    options.abandoned = [] { return false; };
    EXPECT_EQ(renderer.render(cam, 120, 90, options).pixels, whole.pixels);
    EXPECT_EQ(renderer.render(cam, 120, 90).pixels, whole.pixels);
}
