// Warm-up fits: an idle server fits the eps around the last one into the box cache at idle priority, each
// eps once, a new job cancels a running warm-up, and --no-warm-up means none; `vots serve` warms up unless
// told not to (the library's ServerOptions do not).
#include "LoopbackServer.h"
#include "ServeProcess.h"
#include "ServerFixture.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <utility>

namespace vots::test {
namespace {

using namespace std::chrono_literals;

nlohmann::json postFit(httplib::Client& c, const std::string& dataset, const std::string& eps) {
    const auto res =
        c.Post("/api/fit", R"({"dataset":")" + dataset + R"(","eps":)" + eps + "}", "application/json");
    EXPECT_TRUE(res && (res->status == 200 || res->status == 202)) << (res ? res->body : "no response");
    return bodyJson(res);
}

/// waitForStats on the stats' warmUps part; returns the last warmUps.
template <class Until> nlohmann::json waitForWarmUps(httplib::Client& c, Until until) {
    return waitForStats(c, [&](const nlohmann::json& stats) { return until(stats["warmUps"]); })["warmUps"];
}

TEST(ServerWarmUp, AnIdleServerFitsTheEpsAroundTheLastOneEachOnce) {
    ServerWorld world;
    auto options = world.options();
    options.withRenderer = false;
    options.warmUpFits = true;
    LoopbackServer server(options);
    auto c = server.client();
    const auto job = waitForJob(*c, postFit(*c, MRI_BRAIN, "\"8%\""));
    ASSERT_EQ(job["state"], "done") << job.dump();
    // 8 % -> 6.4, 10 and 4 %, in that order (WarmUpFits::FACTORS).
    const auto warm = waitForWarmUps(
        *c, [](const nlohmann::json& w) { return w["finished"] == 3 && !w["running"].get<bool>(); });
    EXPECT_EQ(warm["started"], 3) << warm.dump();
    EXPECT_EQ(warm["cancelled"], 0) << warm.dump();
    EXPECT_FLOAT_EQ(warm["lastEps"].get<float>(), job["eps"].get<float>() / 2) << warm.dump();
    // 4 % -> 3.2, 5 and 2 %; 2 % -> 1.6, 2.5 and 1 %; 1 % -> 1.25 % only (the others are below 1 % of the
    // range); 8 % again -> none (all three were fitted). A warm-up starts a moment after its fit is done
    // (the worker first returns freed memory), so each round waits for its warm-ups to have started and
    // finished before the next fit.
    const std::pair<const char*, int> rounds[] = {
        {"\"4%\"", 6}, {"\"2%\"", 9}, {"\"1%\"", 10}, {"\"8%\"", 10}};
    for (const auto& [eps, started] : rounds) {
        ASSERT_EQ(waitForJob(*c, postFit(*c, MRI_BRAIN, eps))["state"], "done");
        waitForWarmUps(*c, [started = started](const nlohmann::json& w) {
            return w["started"] == started && !w["running"].get<bool>();
        });
    }
    std::this_thread::sleep_for(200ms);
    const auto last = bodyJson(c->Get("/api/stats"))["warmUps"];
    EXPECT_EQ(last["started"], 10) << last.dump();
    EXPECT_EQ(last["finished"], 10) << last.dump();
    EXPECT_FLOAT_EQ(last["lastEps"].get<float>(), job["eps"].get<float>() / 8 * 1.25f) << last.dump();
}

TEST(ServerWarmUp, ANewJobCancelsARunningWarmUp) {
    ServerWorld world;
    // Uniform noise: at eps = a quarter of the range the fit needs many small boxes, so the warm-up
    // (the first at 0.8 of the first fit's eps) runs long enough to be caught.
    std::mt19937 random(7);
    std::string noise = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\nencoding: raw\n\n";
    for (int i = 0; i < 64 * 64 * 64; ++i)
        noise.push_back(static_cast<char>(random() & 0xff));
    world.dir().write("data/noise.nrrd", noise);
    auto options = world.options();
    options.withRenderer = false;
    options.warmUpFits = true;
    LoopbackServer server(options);
    auto c = server.client();
    ASSERT_EQ(waitForJob(*c, postFit(*c, "noise", "128"))["state"], "done");
    const auto running = waitForWarmUps(*c, [](const nlohmann::json& w) { return w["started"] == 1; });
    ASSERT_EQ(running["started"], 1) << running.dump();
    const auto next = waitForJob(*c, postFit(*c, "noise", "250"));
    EXPECT_EQ(next["state"], "done") << next.dump();
    const auto warm = waitForWarmUps(*c, [](const nlohmann::json& w) { return !w["running"].get<bool>(); });
    EXPECT_EQ(warm["cancelled"], 1) << warm.dump(); // the second job's own warm-up may have finished
}

TEST(ServerWarmUp, NoneWhenTurnedOff) {
    ServerWorld world;
    auto options = world.options();
    options.withRenderer = false;
    options.warmUpFits = false;
    LoopbackServer server(options);
    auto c = server.client();
    ASSERT_EQ(waitForJob(*c, postFit(*c, MRI_BRAIN, "\"8%\""))["state"], "done");
    std::this_thread::sleep_for(300ms);
    EXPECT_EQ(bodyJson(c->Get("/api/stats"))["warmUps"]["started"], 0);
}

TEST(ServerWarmUp, VotsServeWarmsUpUnlessToldNotTo) {
    ServerWorld world;
    ServeProcess serve(world, {}, /*warmUps=*/true);
    ASSERT_GT(serve.port(), 0);
    auto c = serve.client();
    ASSERT_EQ(waitForJob(*c, postFit(*c, MRI_BRAIN, "\"8%\""))["state"], "done");
    const auto warm = waitForWarmUps(*c, [](const nlohmann::json& w) { return w["started"].get<int>() > 0; });
    EXPECT_GT(warm["started"].get<int>(), 0) << warm.dump();
}

} // namespace
} // namespace vots::test
