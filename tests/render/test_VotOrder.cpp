// Record orders: Z-order of the boxes' low corners, ties in file order.
#include "VotOrder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <tuple>

using namespace vots;

namespace {

// Morton code the slow way: bit b of axis a goes to bit 3b + a.
std::uint64_t morton(const std::array<int, 3>& p) {
    std::uint64_t code = 0;
    for (int b = 0; b < 21; ++b)
        for (int a = 0; a < 3; ++a)
            code |= static_cast<std::uint64_t>((p[static_cast<std::size_t>(a)] >> b) & 1) << (3 * b + a);
    return code;
}

} // namespace

TEST(VotOrder, SpatialOrderIsZOrderWithTiesInFileOrder) {
    std::mt19937 random(7);
    for (const int side : {1, 40, 300, 5000}) { // one key digit, two and more
        std::uniform_int_distribution<int> coordinate(0, side - 1);
        std::vector<fit::Vot> vots(3000);
        for (fit::Vot& v : vots)
            for (std::size_t a = 0; a < 3; ++a) {
                v.box.lo[a] = coordinate(random);
                v.box.hi[a] = v.box.lo[a] + 1;
            }
        std::vector<std::tuple<std::uint64_t, std::size_t>> expected;
        for (std::size_t i = 0; i < vots.size(); ++i)
            expected.emplace_back(morton(vots[i].box.lo), i);
        std::sort(expected.begin(), expected.end());
        const std::vector<std::size_t> order = render::spatialOrder(vots);
        ASSERT_EQ(order.size(), vots.size());
        for (std::size_t i = 0; i < order.size(); ++i)
            ASSERT_EQ(order[i], std::get<1>(expected[i])) << "side " << side << ", position " << i;
    }
    EXPECT_TRUE(render::spatialOrder({}).empty());
}
