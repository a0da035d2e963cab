// The z cells each rank owns: they tile the grid's cells in rank order, and the Vots each rank draws.
#include "vots/dist/RankCells.h"

#include <gtest/gtest.h>

namespace vots::test {
namespace {

TEST(RankCells, TileTheCellsInRankOrderWithSizesDifferingByAtMostOne) {
    for (const int cells : {1, 2, 3, 7, 39, 40, 999}) {
        for (const int ranks : {1, 2, 3, 4, 5, 16}) {
            int next = 0, smallest = cells, largest = 0;
            for (int r = 0; r < ranks; ++r) {
                const dist::RankCells own = dist::cellsOfRank(cells, r, ranks);
                EXPECT_EQ(own.first, next) << cells << " cells, rank " << r << " of " << ranks;
                EXPECT_GE(own.end, own.first);
                smallest = std::min(smallest, own.end - own.first);
                largest = std::max(largest, own.end - own.first);
                next = own.end;
            }
            EXPECT_EQ(next, cells) << cells << " cells on " << ranks << " ranks";
            EXPECT_LE(largest - smallest, 1) << cells << " cells on " << ranks << " ranks";
        }
    }
    EXPECT_TRUE(dist::cellsOfRank(2, 0, 4).empty()) << "more ranks than cells leaves some with none";
}

fit::Vot votSpanningZ(int lo, int hi) {
    fit::Vot v{};
    v.box.lo = {0, 0, lo};
    v.box.hi = {1, 1, hi};
    return v;
}

TEST(RankCells, WholeRaysTakeTheVotsStartingInTheCellsCutRaysEveryVotMeetingThem) {
    fit::VotSpace space;
    space.dims = {2, 2, 11};
    space.vots = {votSpanningZ(0, 3), votSpanningZ(3, 6), votSpanningZ(4, 10)};
    const dist::RankCells cells{5, 10};
    EXPECT_EQ(dist::votsOfCells(space, cells, false).vots.size(), 0u) << "none starts in [5, 10)";
    EXPECT_EQ(dist::votsOfCells(space, cells, true).vots.size(), 2u) << "[3, 6) and [4, 10) meet [5, 10)";
    EXPECT_EQ(dist::votsOfCells(space, {0, 5}, false).vots.size(), 3u);
}

TEST(RankCells, AFitOfTheCellsPlanesIsMovedIntoTheGridOfTheWhole) {
    fit::VotSpace space;
    space.vots = {votSpanningZ(0, 2)};
    space.vots[0].p = {0.5f, 0.5f, 1.f};
    fit::Volume whole;
    whole.dims = {4, 5, 30};
    whole.spacing = {1.0, 2.0, 3.0};
    dist::placeCellsFitInGrid(space, {12, 20}, whole);
    EXPECT_EQ(space.vots[0].box.lo[2], 12);
    EXPECT_EQ(space.vots[0].box.hi[2], 14);
    EXPECT_EQ(space.vots[0].p[2], 13.f);
    EXPECT_EQ(space.dims, whole.dims);
    EXPECT_EQ(space.spacing, whole.spacing);
}

} // namespace
} // namespace vots::test
