// Skip boxes: grown only over background and Vots whose bound is at most their own Vot's.
#include "SkipBoxes.h"

#include <gtest/gtest.h>

#include <random>

namespace vots::render {
namespace {

struct Scene {
    std::array<int, 3> cells{24, 20, 18};
    std::vector<GpuVot> vots;
    std::vector<std::uint32_t> cellVot; // x fastest; background: vots.size() and up
    VotWalkGrid grid;                   // the walk grid of the Vots, with its empty blocks
};

// Boxes of 2 or 3 cells tiling the grid, every fifth left out as background, random bounds.
Scene randomScene(std::uint32_t seed) {
    Scene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> bound(0.f, 100.f);
    const std::size_t count = static_cast<std::size_t>(s.cells[0] * s.cells[1] * s.cells[2]);
    s.cellVot.assign(count, 0u);
    std::vector<std::array<int, 6>> boxes;
    for (int z = 0; z < s.cells[2]; z += 3)
        for (int y = 0; y < s.cells[1]; y += 2)
            for (int x = 0; x < s.cells[0]; x += 3)
                boxes.push_back({x, y, z, std::min(x + 3, s.cells[0]), std::min(y + 2, s.cells[1]),
                                 std::min(z + 3, s.cells[2])});
    std::vector<std::uint32_t> id(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        if (i % 5 == 4) continue;
        GpuVot v{};
        for (int a = 0; a < 3; ++a)
            v.lo[a] = float(boxes[i][a]), v.hi[a] = float(boxes[i][3 + a]);
        v.upperBound = bound(rng);
        id[i] = static_cast<std::uint32_t>(s.vots.size());
        s.vots.push_back(v);
    }
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const auto& b = boxes[i];
        for (int z = b[2]; z < b[5]; ++z)
            for (int y = b[1]; y < b[4]; ++y)
                for (int x = b[0]; x < b[3]; ++x)
                    s.cellVot[static_cast<std::size_t>((z * s.cells[1] + y) * s.cells[0] + x)] =
                        i % 5 == 4 ? static_cast<std::uint32_t>(s.vots.size() + i) : id[i];
    }
    std::string why;
    std::optional<VotWalkGrid> grid =
        buildVotWalkGrid(s.vots, {s.cells[0] + 1, s.cells[1] + 1, s.cells[2] + 1}, 3, &why);
    EXPECT_TRUE(grid) << why;
    if (grid) s.grid = std::move(*grid);
    return s;
}

SkipGrowthInput growthInput(const Scene& s) {
    SkipGrowthInput in;
    in.grid = s.grid;
    for (const GpuVot& v : s.vots) {
        in.votBoxes.push_back(cellBlockOf(v));
        in.votBounds.push_back(v.upperBound);
    }
    return in;
}

TEST(SkipBoxes, CoverOnlyWhatTheirVotsBoundAlsoCulls) {
    const Scene s = randomScene(7u);
    const std::atomic<bool> cancel{false};
    const std::vector<CellBlock> skip = growSkipBoxes(growthInput(s), cancel);
    ASSERT_EQ(skip.size(), s.vots.size() + s.grid.emptyBlocks.size());
    std::size_t grownBoxes = 0;
    for (std::size_t i = 0; i < s.vots.size(); ++i) {
        const GpuVot& v = s.vots[i];
        const CellBlock& b = skip[i];
        bool grown = false;
        for (int a = 0; a < 3; ++a) {
            ASSERT_LE(b.lo[a], int(v.lo[a]));
            ASSERT_GE(b.hi[a], int(v.hi[a]));
            ASSERT_GE(b.lo[a], 0);
            ASSERT_LE(b.hi[a], s.cells[a]);
            ASSERT_LE(int(v.lo[a]) - b.lo[a], MAX_SKIP_GROWTH);
            ASSERT_LE(b.hi[a] - int(v.hi[a]), MAX_SKIP_GROWTH);
            grown = grown || b.lo[a] < int(v.lo[a]) || b.hi[a] > int(v.hi[a]);
        }
        grownBoxes += grown ? 1 : 0;
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x) {
                    const std::uint32_t id =
                        s.cellVot[static_cast<std::size_t>((z * s.cells[1] + y) * s.cells[0] + x)];
                    if (id < s.vots.size()) {
                        ASSERT_LE(s.vots[id].upperBound, v.upperBound) << i;
                    }
                }
    }
    EXPECT_GT(grownBoxes, s.vots.size() / 4); // growth happens, not only the own boxes
    // Empty blocks grow over background only: the walk steps over them whatever the pixel's max.
    std::size_t grownEmpty = 0;
    for (std::size_t k = 0; k < s.grid.emptyBlocks.size(); ++k) {
        const CellBlock& own = s.grid.emptyBlocks[k];
        const CellBlock& b = skip[s.vots.size() + k];
        for (int a = 0; a < 3; ++a) {
            ASSERT_LE(b.lo[a], own.lo[a]);
            ASSERT_GE(b.hi[a], own.hi[a]);
        }
        grownEmpty += b.lo != own.lo || b.hi != own.hi ? 1 : 0;
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x)
                    ASSERT_GE(s.cellVot[static_cast<std::size_t>((z * s.cells[1] + y) * s.cells[0] + x)],
                              s.vots.size());
    }
    EXPECT_GT(grownEmpty, 0u);
}

TEST(SkipBoxes, CancelledGrowthReturnsNothing) {
    const Scene s = randomScene(8u);
    const std::atomic<bool> cancel{true};
    EXPECT_TRUE(growSkipBoxes(growthInput(s), cancel).empty());
}

} // namespace
} // namespace vots::render
