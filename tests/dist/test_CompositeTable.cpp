// The one composite table and FrameComposite's arithmetic per operation.
#include "vots/dist/CompositeOp.h"
#include "vots/dist/FrameComposite.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace vots::test {
namespace {

using dist::CompositeOp;
using dist::RankSource;
using render::RenderMode;

TEST(CompositeTable, EveryModeAndSourceHasItsOperation) {
    EXPECT_EQ(dist::compositeOpFor(RenderMode::Mip, RankSource::Vots), CompositeOp::Max);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::MinIp, RankSource::Vots), CompositeOp::MinOfCutRays);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::Aip, RankSource::Vots), CompositeOp::WeightedMean);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::Density, RankSource::Vots), CompositeOp::Min);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::Mip, RankSource::Grid), CompositeOp::Max);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::MinIp, RankSource::Grid), CompositeOp::Min);
    EXPECT_EQ(dist::compositeOpFor(RenderMode::Aip, RankSource::Grid), CompositeOp::Sum);
    EXPECT_THROW(dist::compositeOpFor(RenderMode::Density, RankSource::Grid), std::logic_error);
    EXPECT_FALSE(dist::compositesCutRays(RenderMode::Mip));
    EXPECT_TRUE(dist::compositesCutRays(RenderMode::MinIp));
    EXPECT_TRUE(dist::compositesCutRays(RenderMode::Aip));
    EXPECT_FALSE(dist::compositesCutRays(RenderMode::Density));
}

dist::RankFrame frameOf(std::vector<float> pixels, RankSource source = RankSource::Vots) {
    const int width = static_cast<int>(pixels.size());
    return {{width, 1, std::move(pixels)}, std::nullopt, source, std::nullopt};
}

TEST(CompositeTable, MaxAndMinOfCutRaysWhereANothingNeverWins) {
    dist::FrameComposite mip(RenderMode::Mip, frameOf({1.f, -INFINITY, 5.f}));
    mip.add(frameOf({2.f, 3.f, -INFINITY}));
    EXPECT_EQ(mip.finish().pixels, (std::vector<float>{2.f, 3.f, 5.f}));

    dist::FrameComposite minip(RenderMode::MinIp, frameOf({1.f, -INFINITY, -INFINITY}));
    minip.add(frameOf({2.f, 3.f, -INFINITY}));
    EXPECT_EQ(minip.finish().pixels, (std::vector<float>{1.f, 3.f, -INFINITY}))
        << "a cut ray that takes nothing is no minimum; no rank's taking anything stays nothing";

    dist::FrameComposite gridMinip(RenderMode::MinIp, frameOf({1.f, INFINITY}, RankSource::Grid));
    gridMinip.add(frameOf({2.f, INFINITY}, RankSource::Grid));
    EXPECT_EQ(gridMinip.finish().pixels, (std::vector<float>{1.f, INFINITY}));
}

TEST(CompositeTable, TheAipIsTheLengthWeightedMeanOfTheVotsAndTheSumOfTheGrids) {
    dist::RankFrame lower = frameOf({10.f, 4.f, -INFINITY});
    lower.lengths = render::FloatImage{3, 1, {1.f, 3.f, 0.f}};
    dist::RankFrame upper = frameOf({20.f, -INFINITY, -INFINITY});
    upper.lengths = render::FloatImage{3, 1, {3.f, 0.f, 0.f}};
    dist::FrameComposite aip(RenderMode::Aip, lower);
    aip.add(upper);
    EXPECT_EQ(aip.finish().pixels, (std::vector<float>{17.5f, 4.f, -INFINITY}));

    dist::FrameComposite grid(RenderMode::Aip, frameOf({1.5f, 2.f}, RankSource::Grid));
    grid.add(frameOf({0.25f, 0.f}, RankSource::Grid));
    EXPECT_EQ(grid.finish().pixels, (std::vector<float>{1.75f, 2.f}));
}

TEST(CompositeTable, FramesThatDoNotMatchAreRefused) {
    dist::FrameComposite mip(RenderMode::Mip, frameOf({1.f, 2.f}));
    EXPECT_THROW(mip.add(frameOf({1.f})), std::runtime_error);
    EXPECT_THROW(mip.add(frameOf({1.f, 2.f}, RankSource::Grid)), std::runtime_error);
    EXPECT_THROW(dist::FrameComposite(RenderMode::Aip, frameOf({1.f})), std::logic_error) << "no lengths";
    EXPECT_THROW(dist::FrameComposite(RenderMode::Density, frameOf({1.f})), std::logic_error) << "no range";
}

TEST(CompositeTable, TheDensityIsShownOverTheUnionOfTheRanksRanges) {
    dist::RankFrame a = frameOf({3.f});
    a.displayRange = std::array<float, 2>{0.f, 4.f};
    dist::RankFrame b = frameOf({2.f});
    b.displayRange = std::array<float, 2>{0.f, 6.f};
    dist::FrameComposite density(RenderMode::Density, a);
    density.add(b);
    EXPECT_EQ(density.finish().pixels, std::vector<float>{2.f});
    EXPECT_EQ(density.displayRange(), (std::array<float, 2>{0.f, 6.f}));
}

} // namespace
} // namespace vots::test
