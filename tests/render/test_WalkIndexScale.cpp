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
    walk.setStrategy(Strategy::Walk);
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

TEST(WalkIndexScale, BricksInsideOneVotOrBackgroundAreNamedWithoutTables) {
    // 39^3 cells in bricks of 8 (the last partial): a large Vot over whole bricks and beyond a brick
    // border, a small one inside a brick, and background bricks that touch neither.
    constexpr std::array<int, 3> DIMS{40, 40, 40};
    std::vector<GpuVot> vots(2);
    for (int a = 0; a < 3; ++a) {
        vots[0].lo[a] = 0.0f, vots[0].hi[a] = a == 2 ? 19.0f : 24.0f;
        vots[1].lo[a] = 33.0f, vots[1].hi[a] = 35.0f;
    }
    std::string why;
    const auto grid = buildVotWalkGrid(vots, DIMS, 3, &why);
    ASSERT_TRUE(grid) << why;
    auto inside = [](const GpuVot& v, int x, int y, int z) {
        return float(x) >= v.lo[0] && float(x) < v.hi[0] && float(y) >= v.lo[1] && float(y) < v.hi[1] &&
               float(z) >= v.lo[2] && float(z) < v.hi[2];
    };
    std::vector<int> covered(39 * 39 * 39, 0);
    for (const CellBlock& b : grid->emptyBlocks)
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x)
                    ++covered[static_cast<std::size_t>((z * 39 + y) * 39 + x)];
    for (int z = 0; z < 39; ++z)
        for (int y = 0; y < 39; ++y)
            for (int x = 0; x < 39; ++x) {
                const std::uint32_t id = blockAt(*grid, {x, y, z});
                const int expected = inside(vots[0], x, y, z) ? 0 : inside(vots[1], x, y, z) ? 1 : -1;
                const int count = covered[static_cast<std::size_t>((z * 39 + y) * 39 + x)];
                if (expected >= 0) {
                    ASSERT_EQ(id, std::uint32_t(expected)) << x << "," << y << "," << z;
                    ASSERT_EQ(count, 0) << x << "," << y << "," << z;
                } else {
                    ASSERT_GE(id, vots.size()) << x << "," << y << "," << z;
                    ASSERT_EQ(count, 1) << x << "," << y << "," << z;
                    const CellBlock& b = grid->emptyBlocks[id - vots.size()];
                    ASSERT_TRUE(x >= b.lo[0] && x < b.hi[0] && y >= b.lo[1] && y < b.hi[1] && z >= b.lo[2] &&
                                z < b.hi[2]);
                }
            }
    // Bricks wholly in Vot 0 (x, y < 3, z < 2) and bricks Vot 1 does not reach past (x, y, z >= 3, with
    // Vot 1 inside brick 4) hold one palette entry and no cell table; a brick wholly in background is
    // one empty block of its own extent.
    const PalettedCells& cells = grid->index;
    auto paletteSize = [&](std::size_t brick) {
        const std::uint32_t end = brick + 1 < cells.paletteStart.size() ? cells.paletteStart[brick + 1]
                                                                        : std::uint32_t(cells.palette.size());
        return end - cells.paletteStart[brick];
    };
    auto brickOf = [&](int x, int y, int z) { return std::size_t((z * 5 + y) * 5 + x); };
    ASSERT_EQ(grid->bricks, (std::array<int, 3>{5, 5, 5}));
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) {
                EXPECT_EQ(paletteSize(brickOf(x, y, z)), 1u);
                EXPECT_EQ(cells.palette[cells.paletteStart[brickOf(x, y, z)]], 0u);
            }
    EXPECT_EQ(paletteSize(brickOf(0, 0, 2)), 2u) << "Vot 0 ends inside the brick at z = 16..23";
    EXPECT_GT(paletteSize(brickOf(4, 4, 4)), 2u) << "Vot 1 and the background blocks around it";
    EXPECT_EQ(paletteSize(brickOf(3, 3, 3)), 1u);
    EXPECT_EQ(cells.cellTable[brickOf(3, 3, 3)] & ((1u << CELL_TABLE_CODE_BITS) - 1), 0u);
}
