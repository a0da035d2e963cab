// Polling a server job (a PACS series open, a sweep sent to a PACS) from its 202 answer until it ends.
#pragma once

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace vots::test {

/// Every answer seen, from the POST's 202 to the first that is done, failed or cancelled, polling
/// `pollPrefix` + id every 50 ms (about two minutes at most).
inline std::vector<nlohmann::json> pollJob(httplib::Client& c, const httplib::Result& posted,
                                           const std::string& pollPrefix) {
    EXPECT_TRUE(posted);
    if (!posted) return {};
    EXPECT_EQ(posted->status, 202) << posted->body;
    std::vector<nlohmann::json> seen{nlohmann::json::parse(posted->body)};
    if (!seen.back().contains("id")) return seen;
    const std::string poll = pollPrefix + std::to_string(seen.back()["id"].get<std::uint64_t>());
    for (int i = 0; i < 2400; ++i) {
        const std::string state = seen.back()["state"];
        if (state == "done" || state == "failed" || state == "cancelled") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        const auto res = c.Get(poll.c_str());
        EXPECT_TRUE(res && res->status == 200);
        if (!res) break;
        seen.push_back(nlohmann::json::parse(res->body));
    }
    return seen;
}

} // namespace vots::test
