// EpsLadder: the slider's steps are the E24 percentages of the range with the default among them, and the
// rungs a warm-up fits lie either side of an eps, nearest first.
#include "fits/EpsLadder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace vots::server {
namespace {

Dataset volumeOverRange(float lo, float hi, float defaultEps) {
    Dataset dataset;
    dataset.kind = DatasetKind::Volume;
    dataset.range = {lo, hi};
    dataset.defaultEps = defaultEps;
    return dataset;
}

TEST(EpsLadder, E24PercentagesOfTheRangeAtThreeDigitsWithTheDefault) {
    // A CT's range: 4095 HU. 2 % is 81.9 HU, already three digits; 2.2 % is 90.09, kept as 90.1.
    const auto ladder = epsLadder(volumeOverRange(-1024.f, 3071.f, 81.9f));
    ASSERT_EQ(ladder.size(), 24u + 24u + 17u + 1u); // 0.1-0.91 %, 1-9.1 %, 10-47 %, then 50 %
    EXPECT_NEAR(ladder.front(), 4.095, 0.006);      // 0.1 % of 4095 = 4.095: 4.09 or 4.10
    EXPECT_EQ(ladder.back(), 2050);                 // 50 % = 2047.5
    const auto two = std::find(ladder.begin(), ladder.end(), double{81.9f});
    ASSERT_NE(two, ladder.end());
    EXPECT_EQ(*(two + 1), 90.1); // the decimal, not a float near it: JSON writes "90.1"
    EXPECT_EQ(*(two - 1), 73.7); // 1.8 % = 73.71
    EXPECT_TRUE(std::is_sorted(ladder.begin(), ladder.end()));
}

TEST(EpsLadder, TheDefaultReplacesTheRungNearestIt) {
    // A default 1 % off the 2 % rung takes its place; one between rungs is added.
    const auto near = epsLadder(volumeOverRange(0.f, 1000.f, 20.2f));
    EXPECT_EQ(std::count(near.begin(), near.end(), 20.0), 0);
    EXPECT_EQ(std::count(near.begin(), near.end(), double{20.2f}), 1);
    EXPECT_EQ(near.size(), 66u);
    const auto between = epsLadder(volumeOverRange(0.f, 1000.f, 21.f));
    EXPECT_EQ(std::count(between.begin(), between.end(), 21.0), 1);
    EXPECT_EQ(between.size(), 67u);
}

TEST(EpsLadder, NoneForAVotSpaceFileOrAnEmptyRange) {
    Dataset vots = volumeOverRange(0.f, 255.f, 5.1f);
    vots.kind = DatasetKind::Vots;
    EXPECT_TRUE(epsLadder(vots).empty());
    EXPECT_TRUE(epsLadder(volumeOverRange(7.f, 7.f, 1.f)).empty());
}

TEST(EpsLadder, RungsAroundAnEpsAlternateNearestFirstWithoutTheEpsItself) {
    const std::vector<double> ladder{10, 11, 12, 13, 15, 16, 18, 20};
    EXPECT_EQ(rungsAround(ladder, 13, 4), (std::vector<double>{12, 15, 11, 16}));
    // Off the ladder: the rungs either side first, the nearer (15 / 14 < 14 / 13) first.
    EXPECT_EQ(rungsAround(ladder, 14, 2), (std::vector<double>{15, 13}));
    // At an end, the other side alone; never more than the ladder holds.
    EXPECT_EQ(rungsAround(ladder, 20, 3), (std::vector<double>{18, 16, 15}));
    EXPECT_EQ(rungsAround(ladder, 10, 100).size(), 7u);
    EXPECT_TRUE(rungsAround(ladder, 0, 4).empty());
    EXPECT_TRUE(rungsAround({}, 5, 4).empty());
}

TEST(EpsLadder, DraftsComeFromTheRungNearFourTimesTheEpsUpToATenthOfTheRange) {
    // The CT's ladder: 2 % (81.9 HU) drafts from 8.2 % (336), the rung nearest 4 x 81.9 = 327.6.
    const auto ladder = epsLadder(volumeOverRange(-1024.f, 3071.f, 81.9f));
    const double span = 4095;
    EXPECT_EQ(draftRung(ladder, 81.9, span), 336.0);
    // 0.5 % (20.5 HU): 2 %, the default itself, which the server fits anyway.
    EXPECT_EQ(draftRung(ladder, 20.5, span), double{81.9f});
    // 4.3 % would draft from 17.2 %: capped at 10 % (410 HU), still 2.3 x coarser.
    EXPECT_EQ(draftRung(ladder, 176.0, span), 410.0);
    // From 7.5 % the cap leaves less than 1.5 x: no draft fit, the drafts are drawn at eps.
    EXPECT_EQ(draftRung(ladder, 307.0, span), std::nullopt);
    EXPECT_EQ(draftRung(ladder, 0.0, span), std::nullopt);
    EXPECT_EQ(draftRung({}, 81.9, span), std::nullopt);
}

} // namespace
} // namespace vots::server
