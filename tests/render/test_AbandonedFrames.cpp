// A frame drawn in bands so that it can be given up: the same pixels as one pass, and abandoned when asked.
#include "RenderTestSupport.h"

#include "vots/render/CameraText.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

using namespace vots;
using namespace vots::render;

namespace {

// A cubic over 40^3 samples in boxes of 5 cells: disjoint boxes, so the walk draws it.
const fit::VotSpace& cubicSpace() {
    static const fit::VotSpace space =
        test::polynomialVotSpace(test::randomPolynomial(3, 40, 100.0, 7), {40, 40, 40}, 5);
    return space;
}

// The fragment walk, the one that draws in bands (a GPU's compute walk draws a frame whole).
void useFragmentWalk(VotRenderer& walk) {
    walk.setStrategy(VotRenderer::Strategy::Walk);
    walk.setWalkShader(VotRenderer::WalkShader::Fragment);
    walk.upload(cubicSpace());
}

RenderOptions asking(RenderMode mode, std::function<bool()> abandoned) {
    RenderOptions options{mode};
    options.abandoned = std::move(abandoned);
    return options;
}

} // namespace

TEST(AbandonedFrames, BandsGiveTheSamePixelsAsOnePass) {
    test::glContext();
    VotRenderer walk;
    useFragmentWalk(walk);
    ASSERT_EQ(walk.mipStrategy(), VotRenderer::Strategy::Walk);
    // Heights that are and are not whole bands, in every mode the walk draws, in both projections.
    for (const char* text : {"az=31,el=23,zoom=1.3", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"})
        for (RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip})
            for (auto [width, height] : {std::pair{300, 900}, std::pair{257, 600}, std::pair{64, 333}}) {
                const Camera camera = parseCamera(text);
                int questions = 0;
                const FloatImage banded =
                    walk.render(camera, width, height, asking(mode, [&] { return ++questions < 0; }));
                const FloatImage whole = walk.render(camera, width, height, RenderOptions{mode});
                EXPECT_EQ(banded.pixels, whole.pixels) << text << " " << width << "x" << height;
                // Asked once per band: eight bands of 128 rows for 900, five for 600, and one for 333
                // (fewer rows of 64-pixel tiles than bands: a draft's size, drawn whole).
                EXPECT_EQ(questions, height == 900 ? 8 : height == 600 ? 5 : 1) << height;
            }
}

TEST(AbandonedFrames, AFrameIsGivenUpBetweenBandsAndTheNextIsWhole) {
    test::glContext();
    VotRenderer walk;
    useFragmentWalk(walk);
    const Camera camera = parseCamera("az=31,el=23,zoom=1.3");
    const FloatImage whole = walk.render(camera, 320, 512, RenderOptions{});
    int questions = 0;
    // Wanted for three bands, then no more.
    EXPECT_THROW(walk.render(camera, 320, 512, asking(RenderMode::Mip, [&] { return ++questions > 3; })),
                 FrameAbandoned);
    EXPECT_EQ(questions, 4);
    // Nothing of the abandoned frame's state (scissor, culling) is left for the next frames.
    EXPECT_EQ(walk.render(camera, 320, 512, RenderOptions{}).pixels, whole.pixels);
    const DisplaySettings display = windowForRange(walk.valueRange()[0], walk.valueRange()[1]);
    EXPECT_EQ(
        walk.renderRgba(camera, 320, 512, display, RenderOptions{}).pixels,
        walk.renderRgba(camera, 320, 512, display, asking(RenderMode::Mip, [] { return false; })).pixels);
}
