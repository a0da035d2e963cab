// The start-up dataset (--prepare): with no request at all, the server loads it, fits it at its default
// eps and draws a frame of it, so the viewer's first /render finds the fit done; a name the data
// folders lack prepares nothing.
#include "LoopbackServer.h"
#include "ServerFixture.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace vots::test {
namespace {

using namespace std::chrono_literals;

TEST(ServerStartupDataset, FitsAndDrawsTheDatasetBeforeAnyRequest) {
    ServerWorld world;
    auto options = world.options();
    options.startupDataset = MRI_BRAIN;
    options.warmUpFits = false;
    LoopbackServer server(options);
    auto c = server.client();
    // Done when the fit is there and its frame has been drawn (the upload).
    const auto stats = waitForStats(*c, [](const nlohmann::json& s) {
        return s["fits"].size() == 1 && s["frames"]["count"].get<int>() >= 1;
    });
    ASSERT_TRUE(stats["renderer"]["available"].get<bool>()) << "no EGL context (llvmpipe gives one)";
    ASSERT_EQ(stats["fits"].size(), 1u) << stats.dump();
    EXPECT_EQ(stats["fits"][0]["dataset"], MRI_BRAIN);
    EXPECT_EQ(stats["fits"][0]["source"], "fit");

    // The viewer's first image: the default eps, which the prepared fit answers (no second fit).
    const auto res = c->Get((std::string("/render?dataset=") + MRI_BRAIN + "&size=64x64").c_str());
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    EXPECT_EQ(bodyJson(c->Get("/api/stats"))["fits"].size(), 1u);
    EXPECT_EQ(stats["frames"]["count"], 1) << "the prepared frame, before any request";
    EXPECT_NEAR(std::stod(res->get_header_value("X-Vots-Fit-Seconds")),
                stats["fits"][0]["fitSeconds"].get<double>(), 1e-3)
        << "the image should come from the prepared fit";
}

TEST(ServerStartupDataset, ANameTheDataFoldersLackPreparesNothing) {
    ServerWorld world;
    auto options = world.options();
    options.startupDataset = "cranium";
    options.withRenderer = false;
    LoopbackServer server(options);
    auto c = server.client();
    std::this_thread::sleep_for(300ms);
    const auto stats = bodyJson(c->Get("/api/stats"));
    EXPECT_TRUE(stats["fits"].empty()) << stats.dump();
    EXPECT_EQ(stats["fitJobs"]["active"], 0) << stats.dump();
}

} // namespace
} // namespace vots::test
