// The server's box caches: one per dataset, frame and degree, and within their budget before each fit: the
// least recently used other caches go first, then the asked-for one starts again (its old one lives on with
// the fit that holds it).
#include "SampleVolume.h"
#include "fits/BoxCaches.h"

#include "vots/fit/Fitter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vots::server {
namespace {

// A fit through `cache` grows it by the boxes it tries.
void fitWith(fit::FitCache& cache) {
    const fit::Volume volume = test::sampleVolume({40, 40, 40}, [](int x, int y, int z) {
        return 100.0 * std::sin(0.4 * x) * std::cos(0.3 * y) + 2.0 * z;
    });
    fit::FitOptions options;
    options.eps = 1.f;
    (void)fit::fitVotSpace(volume, options, &cache);
}

std::uint64_t emptyBytes() {
    return fit::FitCache().memoryBytes();
}

TEST(BoxCaches, OneCacheForEachDatasetFrameAndDegree) {
    BoxCaches caches(std::uint64_t{1} << 30);
    const auto a = caches.forFits("a", 0, 3);
    EXPECT_EQ(caches.forFits("a", 0, 3), a);
    EXPECT_NE(caches.forFits("a", 0, 2), a);
    EXPECT_NE(caches.forFits("a", 1, 3), a);
    EXPECT_NE(caches.forFits("b", 0, 3), a);
    EXPECT_EQ(caches.forFits("a", 0, 3), a) << "a fourth cache must not push out the first";
    (void)caches.forFits("c", 0, 3); // a fifth: the least recently used, a/0/2, goes
    EXPECT_EQ(caches.stats().caches, BoxCaches::MAX_KEPT);
    EXPECT_EQ(caches.stats().dropped, 1u);
    EXPECT_EQ(caches.forFits("a", 0, 3), a);
}

TEST(BoxCaches, OverTheBudgetTheLeastRecentlyUsedOtherCacheGoesFirst) {
    fit::FitCache probe;
    fitWith(probe);
    const std::uint64_t grown = probe.memoryBytes();
    ASSERT_GT(grown, 2 * emptyBytes()) << "the fit did not grow the cache";
    // Room for one grown cache and an empty one, not for two grown ones.
    BoxCaches caches(grown + 2 * emptyBytes());
    const auto a = caches.forFits("a", 0, 3);
    fitWith(*a);
    const auto b = caches.forFits("b", 0, 3);
    fitWith(*b);
    EXPECT_EQ(caches.forFits("a", 0, 3), a) << "the cache asked for went instead of the other";
    EXPECT_EQ(caches.stats().dropped, 1u);
    EXPECT_EQ(caches.stats().caches, 1u);
    EXPECT_LE(caches.stats().bytes, caches.stats().budgetBytes);
    EXPECT_NE(caches.forFits("b", 0, 3), b) << "b was let go: a new cache for it";
    EXPECT_EQ(caches.forFits("a", 0, 3), a);
}

TEST(BoxCaches, ACacheOverTheBudgetAloneStartsAgainAndItsFitKeepsTheOld) {
    BoxCaches caches(2 * emptyBytes());
    const auto held = caches.forFits("a", 0, 3); // as a running fit holds it
    fitWith(*held);
    const std::size_t boxes = held->size();
    ASSERT_GT(boxes, 0u);
    const auto fresh = caches.forFits("a", 0, 3);
    EXPECT_NE(fresh, held);
    EXPECT_EQ(fresh->size(), 0u);
    EXPECT_EQ(held->size(), boxes) << "the running fit's cache must stay whole";
    EXPECT_EQ(caches.stats().dropped, 1u);
}

} // namespace
} // namespace vots::server
