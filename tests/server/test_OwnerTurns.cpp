// The render queue's turns between owners (remote addresses): the oldest job of the owner served longest
// ago goes next, so one address's many jobs do not hold back another's one.
#include "frames/OwnerTurns.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace vots::server {
namespace {

/// Serves every job of `queue` (owners, oldest first) by the turns; the owners in the order served.
std::vector<std::string> serveAll(OwnerTurns& turns, std::vector<std::string> queue) {
    std::vector<std::string> order;
    while (!queue.empty()) {
        const std::vector<std::string_view> owners(queue.begin(), queue.end());
        const std::size_t next = turns.pick(owners);
        order.push_back(queue[next]);
        queue.erase(queue.begin() + static_cast<std::ptrdiff_t>(next));
        turns.served(order.back(), std::vector<std::string_view>(queue.begin(), queue.end()));
    }
    return order;
}

TEST(OwnerTurns, AnotherOwnersOneJobGoesBeforeTheRestOfABusyOwnersJobs) {
    OwnerTurns turns;
    EXPECT_EQ(serveAll(turns, {"a", "a", "a", "a", "b"}),
              (std::vector<std::string>{"a", "b", "a", "a", "a"}));
}

TEST(OwnerTurns, OwnersTakeTurnsAndEachOwnersJobsKeepTheirOrder) {
    OwnerTurns turns;
    EXPECT_EQ(serveAll(turns, {"a", "a", "a", "b", "b", "c"}),
              (std::vector<std::string>{"a", "b", "c", "a", "b", "a"}));
    // Served last: a. Now b's job goes before a's older one.
    EXPECT_EQ(turns.pick({"a", "b"}), 1u);
    EXPECT_EQ(turns.pick({"b", "c"}), 1u) << "c was served longer ago than b";
    EXPECT_EQ(turns.pick({"a", "d"}), 1u) << "a newcomer first";
}

TEST(OwnerTurns, ForgetsOnlyOwnersWithNothingWaiting) {
    OwnerTurns turns;
    for (std::size_t i = 0; i <= OwnerTurns::MAX_REMEMBERED; ++i)
        turns.served("owner" + std::to_string(i), {"owner0"});
    // owner0 waits, so it is remembered as served long ago, before owner1 (forgotten: a newcomer).
    EXPECT_EQ(turns.pick({"owner0", "owner1"}), 1u);
    turns.served("last", {});
    EXPECT_EQ(turns.pick({"last", "owner0"}), 1u) << "the owner just served goes last";
}

} // namespace
} // namespace vots::server
