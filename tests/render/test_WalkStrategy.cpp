// The Walk MIP strategy against Raster on a fitted real CT, its cell grid, and its fallback for overlaps.
#include "RenderTestSupport.h"

#include "VotWalkGrid.h"
#include "WalkRecord.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/CameraText.h"
#include "vots/render/VotRenderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace vots;
using namespace vots::render;

namespace {

// Every renderer here is set to the walk: where the context is a CPU rasteriser the MIP's default is the
// splat (test_CpuSplat.cpp).
using Strategy = VotRenderer::Strategy;

// The most any walk record of the space strays from its Vot (WalkRecord.h).
double largestRecordError(const fit::VotSpace& space) {
    double largest = 0.0;
    for (const fit::Vot& vot : space.vots)
        largest = std::max(largest, makeWalkRecord(vot).maxError);
    return largest;
}

// Front, oblique, perspective, and perspective with the eye inside the volume.
constexpr const char* VIEWS[] = {"anterior", "az=30,el=20,zoom=1.2",
                                 "az=-50,el=-30,zoom=1.4,proj=persp,fov=40",
                                 "az=20,el=10,zoom=8,proj=persp,fov=60"};

// The quarter Cranium CT fitted with the default (fast) method: disjoint boxes, so Walk applies.
const fit::VotSpace& headFast(float* epsOut) {
    static float eps = 0;
    static const fit::VotSpace space = [] {
        const fit::Volume volume =
            fit::loadVolume(std::string(VOTS_TEST_DATA_DIR) + "/cranium-quarter_64x64x108_int16.nrrd");
        const auto range = volume.valueRange();
        fit::FitOptions options;
        options.eps = 0.02f * (range[1] - range[0]);
        options.degree = 3;
        options.background = fit::defaultBackground(volume);
        eps = options.eps;
        return fit::fitVotSpace(volume, options).space;
    }();
    *epsOut = eps;
    return space;
}

} // namespace

TEST(WalkStrategy, MatchesRasterOnFittedCt) {
    test::glContext();
    float eps = 0;
    const fit::VotSpace& space = headFast(&eps);
    VotRenderer walk, raster;
    walk.setStrategy(Strategy::Walk);
    walk.upload(space);
    raster.upload(space);
    raster.setStrategy(Strategy::Raster);
    ASSERT_EQ(walk.mipStrategy(), Strategy::Walk);
    ASSERT_EQ(raster.mipStrategy(), Strategy::Raster);
    const auto range = walk.valueRange();
    // The walk evaluates each Vot's 64-byte record, within its maxError of the Vot (WalkRecord.h).
    const double tiny = 1e-5 * (range[1] - range[0]) + largestRecordError(space);
    for (const char* text : VIEWS) {
        const Camera cam = parseCamera(text);
        const FloatImage a = walk.render(cam, 200, 160);
        const FloatImage b = raster.render(cam, 200, 160);
        const test::ImageComparison c = test::compareImages(a, b, tiny);
        // Both evaluate each Vot with the same analytic maximum, so beyond the records' rounding they
        // can differ only where a ray grazes a face shared by two Vots (within 5e-5 voxel): Raster's
        // slack evaluates both, the walk one of them.
        EXPECT_LE(c.finiteMismatch + c.beyondTolerance, a.pixels.size() / 1000) << text;
        EXPECT_LE(c.worst, 2.0 * eps) << text;
        std::cout << text << ": " << c.bitIdentical << " of " << a.pixels.size() << " pixels bit-identical, "
                  << c.beyondTolerance << " beyond " << tiny << ", " << c.finiteMismatch
                  << " background in one only, worst " << c.worst << "\n";
        std::string name = std::string(text).substr(0, 6);
        for (char& ch : name)
            if (ch == '=' || ch == ',') ch = '_';
        test::saveForInspection(a, "walk_" + name);
        test::saveForInspection(b, "raster_" + name);
    }
}

TEST(WalkStrategy, RepeatRendersAreBitIdentical) {
    test::glContext();
    float eps = 0;
    const fit::VotSpace& space = headFast(&eps);
    VotRenderer walk;
    walk.setStrategy(Strategy::Walk);
    walk.upload(space);
    const Camera cam = parseCamera("az=-12.5,el=33,zoom=1.2,pan=0.1:0,proj=persp,fov=35");
    const FloatImage first = walk.render(cam, 128, 96);
    (void)walk.render(parseCamera("left"), 64, 64);
    EXPECT_EQ(first.pixels, walk.render(cam, 128, 96).pixels);
}

TEST(WalkStrategy, ComputeAndFragmentShadersGiveTheSameImage) {
    // GPUs run the walk as a compute shader, llvmpipe on the rasteriser; the image must not depend on
    // the machine. Sizes that are no multiple of the 8x8 work groups test the edges; the off-centre
    // space tests the other shader variant.
    test::glContext();
    float eps = 0;
    const fit::VotSpace& head = headFast(&eps);
    constexpr int N = 17;
    const fit::VotSpace offCentre =
        test::polynomialVotSpace(test::randomPolynomial(3, N, 100.0, 13u), {N, N, N}, 4, 0.37f);
    for (const fit::VotSpace* space : {&head, &offCentre}) {
        VotRenderer fragment, compute;
        fragment.setStrategy(Strategy::Walk);
        compute.setStrategy(Strategy::Walk);
        fragment.setWalkShader(VotRenderer::WalkShader::Fragment);
        compute.setWalkShader(VotRenderer::WalkShader::Compute);
        fragment.upload(*space);
        compute.upload(*space);
        for (const char* text : VIEWS) {
            const Camera cam = parseCamera(text);
            const FloatImage a = fragment.render(cam, 203, 157), b = compute.render(cam, 203, 157);
            std::size_t finite = 0;
            for (float v : a.pixels)
                finite += std::isfinite(v) ? 1 : 0;
            EXPECT_GT(finite, a.pixels.size() / 10) << text; // not a blank image
            const test::ImageComparison c = test::compareImages(a, b, 0.0);
            EXPECT_EQ(c.finiteMismatch + c.beyondTolerance, 0u) << text << ", worst " << c.worst;
        }
    }
}

TEST(WalkStrategy, SkipBoxesChangeNoPixel) {
    test::glContext();
    float eps = 0;
    const fit::VotSpace& space = headFast(&eps);
    VotRenderer settled;
    settled.setStrategy(Strategy::Walk);
    settled.upload(space);
    settled.finishPendingWork(); // skip boxes grown and in use from the first frame on
    std::size_t differing = 0, pixels = 0;
    for (const char* text : VIEWS) {
        const Camera cam = parseCamera(text);
        VotRenderer fresh; // the first frame after an upload always steps Vot by Vot
        fresh.setStrategy(Strategy::Walk);
        fresh.upload(space);
        const FloatImage before = fresh.render(cam, 200, 160);
        const FloatImage after = settled.render(cam, 200, 160);
        ASSERT_EQ(before.pixels.size(), after.pixels.size());
        for (std::size_t i = 0; i < before.pixels.size(); ++i)
            if (before.pixels[i] != after.pixels[i]) ++differing;
        pixels += before.pixels.size();
    }
    std::cout << differing << " of " << pixels << " pixels differ with skip boxes\n";
    EXPECT_EQ(differing, 0u);
}

TEST(WalkStrategy, AnUploadWhileSkipBoxesGrowGetsOnlyItsOwn) {
    // The growth started by the first frame of one Vot-Space is cancelled, not awaited, by the next
    // upload; nothing of it may reach the new space's frames.
    test::glContext();
    float eps = 0;
    const fit::VotSpace& head = headFast(&eps);
    constexpr int N = 17;
    const fit::VotSpace poly =
        test::polynomialVotSpace(test::randomPolynomial(3, N, 100.0, 12u), {N, N, N}, 4);
    const Camera cam = parseCamera("az=30,el=20,zoom=1.2");
    VotRenderer reference;
    reference.setStrategy(Strategy::Walk);
    reference.upload(poly);
    reference.finishPendingWork();
    const FloatImage expected = reference.render(cam, 96, 80);
    VotRenderer r;
    r.setStrategy(Strategy::Walk);
    for (int round = 0; round < 3; ++round) {
        r.upload(head);
        (void)r.render(cam, 96, 80); // starts the head's growth
        r.upload(poly);              // cancels it
        EXPECT_EQ(r.render(cam, 96, 80).pixels, expected.pixels) << round;
        r.finishPendingWork();
        EXPECT_EQ(r.render(cam, 96, 80).pixels, expected.pixels) << round;
    }
}

TEST(WalkStrategy, OffCentreExpansionPointsRenderTheSamePolynomial) {
    // The walk re-expands every Vot around its box centre (WalkRecord.h); a Vot expanded anywhere else
    // in its box must draw the same polynomial as one expanded there.
    test::glContext();
    constexpr int N = 17;
    const test::Polynomial p = test::randomPolynomial(3, N, 100.0, 11u);
    const fit::VotSpace centredSpace = test::polynomialVotSpace(p, {N, N, N}, 4);
    const fit::VotSpace offCentreSpace = test::polynomialVotSpace(p, {N, N, N}, 4, 0.37f);
    VotRenderer centred, offCentre;
    centred.setStrategy(Strategy::Walk);
    offCentre.setStrategy(Strategy::Walk);
    centred.upload(centredSpace);
    offCentre.upload(offCentreSpace);
    ASSERT_EQ(offCentre.mipStrategy(), Strategy::Walk);
    // Each record is within its maxError of its Vot (WalkRecord.h).
    const double recordError = std::max(largestRecordError(centredSpace), largestRecordError(offCentreSpace));
    for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        const FloatImage a = centred.render(cam, 64, 48), b = offCentre.render(cam, 64, 48);
        const test::ImageComparison c =
            test::compareImages(a, b, 1e-3 + 2.0 * recordError); // float rounding at values ~100
        EXPECT_EQ(c.finiteMismatch + c.beyondTolerance, 0u) << text << ", worst " << c.worst;
    }
}

TEST(WalkStrategy, OverlappingBoxesFallBackToRaster) {
    test::glContext();
    constexpr int N = 12;
    const test::Polynomial p = test::randomPolynomial(3, N, 100.0, 3u);
    fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 4);
    VotRenderer disjoint;
    disjoint.setStrategy(Strategy::Walk);
    disjoint.upload(space);
    EXPECT_EQ(disjoint.mipStrategy(), Strategy::Walk);
    space.vots.push_back(space.vots.front()); // the same box twice: overlap
    VotRenderer overlapping;
    overlapping.setStrategy(Strategy::Walk);
    overlapping.upload(space);
    EXPECT_EQ(overlapping.strategy(), Strategy::Walk);
    EXPECT_EQ(overlapping.mipStrategy(), Strategy::Raster);
    const Camera cam = parseCamera("az=30,el=20");
    const FloatImage a = overlapping.render(cam, 64, 48);
    overlapping.setStrategy(Strategy::Raster);
    EXPECT_EQ(a.pixels, overlapping.render(cam, 64, 48).pixels);
}

TEST(WalkStrategy, EmptySpaceRendersBackground) {
    test::glContext();
    fit::VotSpace space;
    space.dims = {10, 12, 14};
    VotRenderer renderer;
    renderer.setStrategy(Strategy::Walk);
    renderer.upload(space);
    EXPECT_EQ(renderer.mipStrategy(), Strategy::Walk);
    const FloatImage img = renderer.render(parseCamera("az=30,el=20"), 32, 32);
    for (float v : img.pixels)
        EXPECT_TRUE(std::isinf(v) && v < 0);
}

TEST(WalkStrategy, GridCoversEveryCellOnce) {
    constexpr int N = 21; // 20 cells: bricks of 8 leave a partial brick
    const test::Polynomial p = test::randomPolynomial(2, N, 10.0, 8u);
    fit::VotSpace space = test::polynomialVotSpace(p, {N, N, N}, 3);
    // Drop every third Vot, so background cells exist between Vots.
    std::vector<GpuVot> vots;
    for (std::size_t i = 0; i < space.vots.size(); i += 3) {
        GpuVot g{};
        for (int a = 0; a < 3; ++a)
            g.lo[a] = float(space.vots[i].box.lo[a]), g.hi[a] = float(space.vots[i].box.hi[a]);
        g.upperBound = float(i);
        vots.push_back(g);
    }
    std::string why;
    const auto grid = buildVotWalkGrid(vots, {N, N, N}, 3, &why);
    ASSERT_TRUE(grid) << why;
    EXPECT_EQ(grid->bricks, (std::array<int, 3>{3, 3, 3}));
    // The Vot of each cell, from the boxes alone (-1: background).
    std::vector<int> votOf(20 * 20 * 20, -1);
    for (std::size_t k = 0; k < vots.size(); ++k)
        for (int z = int(vots[k].lo[2]); z < int(vots[k].hi[2]); ++z)
            for (int y = int(vots[k].lo[1]); y < int(vots[k].hi[1]); ++y)
                for (int x = int(vots[k].lo[0]); x < int(vots[k].hi[0]); ++x)
                    votOf[static_cast<std::size_t>((z * 20 + y) * 20 + x)] = int(k);
    std::vector<int> covered(votOf.size(), 0);
    for (const CellBlock& b : grid->emptyBlocks) {
        for (int a = 0; a < 3; ++a) // inside one brick
            EXPECT_EQ(b.lo[a] / 8, (b.hi[a] - 1) / 8);
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x)
                    ++covered[static_cast<std::size_t>((z * 20 + y) * 20 + x)];
    }
    std::size_t votCells = 0;
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x) {
                const std::size_t i = static_cast<std::size_t>((z * 20 + y) * 20 + x);
                const std::uint32_t id = blockAt(*grid, {x, y, z});
                if (votOf[i] >= 0) {
                    ++votCells;
                    ASSERT_EQ(id, std::uint32_t(votOf[i])) << "cell " << x << "," << y << "," << z;
                    EXPECT_EQ(covered[i], 0);
                } else {
                    ASSERT_GE(id, vots.size()) << "cell " << x << "," << y << "," << z;
                    ASSERT_LT(id, vots.size() + grid->emptyBlocks.size());
                    EXPECT_EQ(covered[i], 1); // empty blocks are disjoint and name their own cells
                    const CellBlock& b = grid->emptyBlocks[id - vots.size()];
                    EXPECT_TRUE(x >= b.lo[0] && x < b.hi[0] && y >= b.lo[1] && y < b.hi[1] && z >= b.lo[2] &&
                                z < b.hi[2]);
                }
            }
    EXPECT_GT(votCells, 0u);
    EXPECT_LT(grid->emptyBlocks.size(), votOf.size() - votCells); // blocks, not single cells
    // Brick maxima: the largest bound of the Vots whose boxes touch the brick.
    auto expectMaxima = [&](const std::vector<float>& maxima, const std::array<int, 3>& count, int side) {
        for (int z = 0; z < count[2]; ++z)
            for (int y = 0; y < count[1]; ++y)
                for (int x = 0; x < count[0]; ++x) {
                    const int at[3] = {x * side, y * side, z * side};
                    float expected = -INFINITY;
                    for (const GpuVot& v : vots) {
                        bool touches = true;
                        for (int a = 0; a < 3; ++a)
                            touches = touches && v.lo[a] < float(at[a] + side) && v.hi[a] > float(at[a]);
                        if (touches) expected = std::max(expected, v.upperBound);
                    }
                    EXPECT_EQ(maxima[static_cast<std::size_t>((z * count[1] + y) * count[0] + x)], expected)
                        << "block " << x << "," << y << "," << z << " of side " << side;
                }
    };
    expectMaxima(grid->brickMax, grid->bricks, 8);

    // What the shader reads: per cell, brick by brick, an index into its brick's palette of ids, kept
    // only for bricks of more than one block, in as few bits as their palette needs.
    const PalettedCells& cells = grid->index;
    ASSERT_EQ(cells.paletteStart.size(), grid->brickMax.size());
    ASSERT_EQ(cells.cellTable.size(), grid->brickMax.size());
    std::size_t tableWords = 0;
    for (std::size_t brick = 0; brick < cells.paletteStart.size(); ++brick) {
        const std::uint32_t start = cells.paletteStart[brick];
        const std::uint32_t end = brick + 1 < cells.paletteStart.size() ? cells.paletteStart[brick + 1]
                                                                        : std::uint32_t(cells.palette.size());
        const std::set<std::uint32_t> distinct(cells.palette.begin() + start, cells.palette.begin() + end);
        EXPECT_EQ(distinct.size(), end - start) << "brick " << brick << " lists an id twice";
        const std::uint32_t code = cells.cellTable[brick] & ((1u << CELL_TABLE_CODE_BITS) - 1);
        if (end - start == 1) {
            EXPECT_EQ(code, 0u) << "brick " << brick << " of one block has a cell table";
        } else {
            const std::uint32_t bits = 1u << (code - 1);
            EXPECT_GE(std::uint64_t{1} << bits, end - start) << "brick " << brick << ": too few bits";
            EXPECT_LT(std::uint64_t{1} << (bits / 2), end - start)
                << "brick " << brick << ": more bits than needed";
            EXPECT_EQ(cells.cellTable[brick] >> CELL_TABLE_CODE_BITS, tableWords) << "brick " << brick;
            tableWords += (512 * bits / 32 + 3) / 4 * 4;
        }
    }
    EXPECT_EQ(std::max<std::size_t>(tableWords, 4), cells.cellWords.size());

    vots.push_back(vots.front());
    EXPECT_FALSE(buildVotWalkGrid(vots, {N, N, N}, 3, &why));
    EXPECT_NE(why.find("overlap"), std::string::npos) << why;
}

TEST(WalkStrategy, EmptyBlocksCoverTallGridsExactlyOnce) {
    // Tall enough for the bricks to be indexed on several cores, with partial bricks in x and y.
    const std::array<int, 3> dims{12, 10, 140};
    std::vector<GpuVot> vots;
    for (int z = 0; z + 3 < dims[2] - 1; z += 7) {
        GpuVot g{};
        const int x = z % 5, y = (z / 7) % 4;
        g.lo[0] = float(x), g.lo[1] = float(y), g.lo[2] = float(z);
        g.hi[0] = float(x + 3), g.hi[1] = float(y + 2), g.hi[2] = float(z + 3);
        g.upperBound = float(z);
        vots.push_back(g);
    }
    std::string why;
    const auto grid = buildVotWalkGrid(vots, dims, 4, &why);
    ASSERT_TRUE(grid) << why;
    const int nx = dims[0] - 1, ny = dims[1] - 1, nz = dims[2] - 1;
    std::vector<int> covered(static_cast<std::size_t>(nx * ny * nz), 0);
    for (const CellBlock& b : grid->emptyBlocks)
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x)
                    ++covered[static_cast<std::size_t>((z * ny + y) * nx + x)];
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (int x = 0; x < nx; ++x) {
                const std::size_t i = static_cast<std::size_t>((z * ny + y) * nx + x);
                const std::uint32_t id = blockAt(*grid, {x, y, z});
                ASSERT_LT(id, vots.size() + grid->emptyBlocks.size()) << x << "," << y << "," << z;
                if (id < vots.size()) {
                    const GpuVot& v = vots[id];
                    EXPECT_TRUE(float(x) >= v.lo[0] && float(x) < v.hi[0] && float(y) >= v.lo[1] &&
                                float(y) < v.hi[1] && float(z) >= v.lo[2] && float(z) < v.hi[2]);
                    EXPECT_EQ(covered[i], 0);
                } else {
                    ASSERT_EQ(covered[i], 1) << x << "," << y << "," << z;
                    const CellBlock& b = grid->emptyBlocks[id - vots.size()];
                    EXPECT_TRUE(x >= b.lo[0] && x < b.hi[0] && y >= b.lo[1] && y < b.hi[1] && z >= b.lo[2] &&
                                z < b.hi[2]);
                }
            }
}
