// The walk on a Vot-Space of more cells than a buffer texture holds texels: the index follows the Vots.
#include "RenderTestSupport.h"

#include "VotWalkGrid.h"

#include "vots/render/CameraText.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace vots;
using namespace vots::render;

namespace {

using Strategy = VotRenderer::Strategy;

// llvmpipe's GL_MAX_TEXTURE_BUFFER_SIZE, which a dense per-cell table (one texel per cell) had to stay
// below, so that the walk fell back to the raster strategy past it.
constexpr std::size_t DENSE_TABLE_LIMIT = std::size_t{1} << 27;

} // namespace

TEST(WalkIndexScale, MoreCellsThanATextureBufferHoldsStayOnTheWalk) {
    test::glContext();
    constexpr std::array<int, 3> DIMS{641, 641, 341};
    ASSERT_GT(std::size_t{640} * 640 * 340, DENSE_TABLE_LIMIT);
    const test::Polynomial p = test::randomPolynomial(3, 640, 100.0, 21u);
    fit::VotSpace space = test::polynomialVotSpace(p, DIMS, 64);
    // Every third Vot dropped: background between Vots, as in a fitted study.
    std::vector<fit::Vot> kept;
    for (std::size_t i = 0; i < space.vots.size(); ++i)
        if (i % 3 != 1) kept.push_back(space.vots[i]);
    space.vots = std::move(kept);

    VotRenderer walk, raster;
    walk.upload(space);
    raster.upload(space);
    raster.setStrategy(Strategy::Raster);
    ASSERT_EQ(walk.mipStrategy(), Strategy::Walk) << "the walk fell back to the raster strategy";
    ASSERT_EQ(raster.mipStrategy(), Strategy::Raster);
    const auto range = walk.valueRange();
    ASSERT_LT(range[0], range[1]);
    for (const char* text : {"az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        const FloatImage a = walk.render(cam, 96, 96);
        const FloatImage b = raster.render(cam, 96, 96);
        // Exact polynomials: the walk's 64-byte records round the higher terms (WalkRecord.h), so the
        // images agree to a small fraction of the range; background must be the same pixels.
        const test::ImageComparison c = test::compareImages(a, b, 1e-3 * (range[1] - range[0]));
        std::cout << text << ": " << c.bitIdentical << " of " << a.pixels.size() << " bit-identical, worst "
                  << c.worst << "\n";
        EXPECT_LE(c.finiteMismatch, a.pixels.size() / 1000) << text;
        EXPECT_EQ(c.beyondTolerance, 0u) << text;
        std::size_t finite = 0;
        for (float v : a.pixels)
            finite += std::isfinite(v) ? 1 : 0;
        EXPECT_GT(finite, a.pixels.size() / 4) << text << ": the Vots cover most of the view";
    }
}
