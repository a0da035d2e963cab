// trimLeastRecentlyUsed, the one size bound of the fit cache and the retrieved series: oldest use first.
#include "LeastRecentlyUsed.h"

#include <gtest/gtest.h>

#include <chrono>
#include <set>

namespace {

using namespace vots::server;
namespace fs = std::filesystem;

CachedOnDisk cached(const std::string& name, int minutesAgo, std::uint64_t bytes) {
    return {name, fs::file_time_type::clock::now() - std::chrono::minutes(minutesAgo), bytes};
}

std::set<std::string> removedBy(std::vector<CachedOnDisk> items, std::uint64_t budget, const fs::path& keep,
                                const std::set<std::string>& failing = {}) {
    std::set<std::string> removed;
    trimLeastRecentlyUsed(std::move(items), budget, keep, [&](const CachedOnDisk& c) {
        if (failing.count(c.path.string())) return false;
        removed.insert(c.path.string());
        return true;
    });
    return removed;
}

TEST(LeastRecentlyUsed, RemovesTheOldestUntilTheRestFit) {
    const std::vector<CachedOnDisk> items = {cached("new", 1, 40), cached("old", 30, 40),
                                             cached("mid", 10, 40)};
    EXPECT_EQ(removedBy(items, 120, "new"), std::set<std::string>{});
    EXPECT_EQ(removedBy(items, 100, "new"), std::set<std::string>{"old"});
    EXPECT_EQ(removedBy(items, 40, "new"), (std::set<std::string>{"old", "mid"}));
}

TEST(LeastRecentlyUsed, KeepsTheOneJustWrittenEvenOverTheBudget) {
    const std::vector<CachedOnDisk> items = {cached("big", 1, 500), cached("old", 30, 10)};
    EXPECT_EQ(removedBy(items, 100, "big"), std::set<std::string>{"old"});
    EXPECT_EQ(removedBy({cached("old", 30, 500)}, 100, "old"), std::set<std::string>{});
}

TEST(LeastRecentlyUsed, AThingThatWouldNotGoStillCountsAndTheNextGoes) {
    const std::vector<CachedOnDisk> items = {cached("new", 1, 40), cached("old", 30, 40),
                                             cached("mid", 10, 40)};
    EXPECT_EQ(removedBy(items, 100, "new", {"old"}), std::set<std::string>{"mid"});
}

} // namespace
