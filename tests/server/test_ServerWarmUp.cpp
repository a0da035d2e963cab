// Warm-up fits: an idle server fits the slider's steps around the last eps ahead at idle priority, each eps
// once, into the fit cache; a new job cancels a running warm-up, and --no-warm-up means none; `vots serve`
// warms up unless told not to (the library's ServerOptions do not).
#include "LoopbackServer.h"
#include "ServeProcess.h"
#include "ServerFixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

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

/// The dataset's entry in /api/datasets.
nlohmann::json datasetEntry(httplib::Client& c, const std::string& dataset) {
    const nlohmann::json list = bodyJson(c.Get("/api/datasets")); // kept: the loop reads into it
    for (const auto& d : list["datasets"])
        if (d["name"] == dataset) return d;
    ADD_FAILURE() << "no dataset " << dataset;
    return {{"epsSteps", nlohmann::json::array()}, {"defaultEps", 0}};
}

/// A server that fits ahead when idle (warm-ups on) and draws nothing.
server::ServerOptions warmingOptions(const ServerWorld& world) {
    auto options = world.options();
    options.withRenderer = false;
    options.warmUpFits = true;
    return options;
}

/// The decimal text a viewer sends for a number it was given as JSON ("88.2").
std::string epsText(double eps) {
    return nlohmann::json(eps).dump();
}

TEST(ServerWarmUp, TheLadderIsRoundPercentagesOfTheRangeWithTheDefaultOnIt) {
    ServerWorld world;
    auto options = world.options();
    options.withRenderer = false;
    LoopbackServer server(options);
    auto c = server.client();
    const nlohmann::json mri = datasetEntry(*c, MRI_BRAIN);
    const auto steps = mri["epsSteps"].get<std::vector<double>>();
    const double span = mri["range"][1].get<double>() - mri["range"][0].get<double>();
    ASSERT_GE(steps.size(), 60u);
    EXPECT_TRUE(std::is_sorted(steps.begin(), steps.end()));
    EXPECT_TRUE(std::adjacent_find(steps.begin(), steps.end()) == steps.end()) << "a step twice";
    EXPECT_NEAR(steps.front() / span, 0.001, 0.001 * 0.01);
    EXPECT_NEAR(steps.back() / span, 0.5, 0.5 * 0.01);
    EXPECT_NE(std::find(steps.begin(), steps.end(), mri["defaultEps"].get<double>()), steps.end());
    for (std::size_t i = 1; i < steps.size(); ++i) { // E24: 6-16 % apart (47 -> 50, 1.3 -> 1.5)
        EXPECT_GT(steps[i] / steps[i - 1], 1.05) << i;
        EXPECT_LT(steps[i] / steps[i - 1], 1.17) << i;
    }
}

TEST(ServerWarmUp, AnIdleServerFitsTheStepsAroundTheLastEpsAheadEachOnce) {
    ServerWorld world;
    LoopbackServer server(warmingOptions(world));
    auto c = server.client();
    const nlohmann::json mri = datasetEntry(*c, MRI_BRAIN);
    const auto steps = mri["epsSteps"].get<std::vector<double>>();
    const auto job = waitForJob(*c, postFit(*c, MRI_BRAIN, "\"8%\""));
    ASSERT_EQ(job["state"], "done") << job.dump();
    const auto warm = waitForWarmUps(
        *c, [](const nlohmann::json& w) { return w["finished"] == 10 && !w["running"].get<bool>(); });
    EXPECT_EQ(warm["started"], 10) << warm.dump();
    EXPECT_EQ(warm["cancelled"], 0) << warm.dump();

    // The five steps either side of 8 % (8.2, 7.5, 9.1, 6.8 ... %) are answered from the fit cache: done
    // in the POST's own answer, no fit job run for them.
    const auto firstAbove = std::upper_bound(steps.begin(), steps.end(), job["eps"].get<double>());
    ASSERT_GE(firstAbove - steps.begin(), 5);
    ASSERT_GE(steps.end() - firstAbove, 5);
    const std::size_t fitsBefore = bodyJson(c->Get("/api/stats"))["fits"].size();
    for (auto step = firstAbove - 5; step != firstAbove + 5; ++step) {
        const auto answer = postFit(*c, MRI_BRAIN, epsText(*step));
        EXPECT_EQ(answer["state"], "done") << epsText(*step) << " " << answer.dump();
    }
    const auto stats = bodyJson(c->Get("/api/stats"));
    EXPECT_EQ(stats["fits"].size(), fitsBefore) << stats["fits"].dump();

    // A warm-up's Vot-Space is the requested fit's: the same count as a server without warm-ups fits.
    ServerWorld coldWorld;
    auto coldOptions = coldWorld.options();
    coldOptions.withRenderer = false;
    LoopbackServer cold(coldOptions);
    auto coldClient = cold.client();
    const std::string far = epsText(*(firstAbove + 4));
    const auto coldJob = waitForJob(*coldClient, postFit(*coldClient, MRI_BRAIN, far));
    const auto warmJob = waitForJob(*c, postFit(*c, MRI_BRAIN, far));
    ASSERT_EQ(coldJob["state"], "done") << coldJob.dump();
    EXPECT_EQ(warmJob["votCount"], coldJob["votCount"]) << warmJob.dump() << coldJob.dump();

    // A cache hit moves the warm-ups with it: the hits above ended at 8 % + 4 steps, whose steps further
    // out are warmed next. Then a fit at 2 % cancels them and warms 2 %'s own steps.
    waitForWarmUps(*c, [](const nlohmann::json& w) { return w["started"].get<int>() > 10; });
    const auto defaultStep = std::find(steps.begin(), steps.end(), mri["defaultEps"].get<double>());
    ASSERT_NE(defaultStep, steps.end()) << "the default is on the ladder";
    ASSERT_EQ(waitForJob(*c, postFit(*c, MRI_BRAIN, epsText(*defaultStep)))["state"], "done");
    waitForWarmUps(*c, [&](const nlohmann::json& w) {
        return w["lastEps"].get<double>() < *defaultStep && !w["running"].get<bool>();
    });
    for (const auto step : {defaultStep - 1, defaultStep + 1}) {
        const auto answer = postFit(*c, MRI_BRAIN, epsText(*step));
        EXPECT_EQ(answer["state"], "done") << epsText(*step) << " " << answer.dump();
    }
}

TEST(ServerWarmUp, AFitAtTwoPercentAlsoWarmsItsDraftRung) {
    ServerWorld world;
    LoopbackServer server(warmingOptions(world));
    auto c = server.client();
    const auto steps = datasetEntry(*c, MRI_BRAIN)["epsSteps"].get<std::vector<double>>();
    const auto job = waitForJob(*c, postFit(*c, MRI_BRAIN, "\"2%\""));
    ASSERT_EQ(job["state"], "done") << job.dump();
    // The drafts' rung: 8.2 %, the step nearest 4 x 2 %, besides the ten steps around 2 %.
    const double eps = job["eps"].get<double>();
    const auto draft = std::min_element(steps.begin(), steps.end(), [&](double a, double b) {
        return std::abs(std::log(a / (4 * eps))) < std::abs(std::log(b / (4 * eps)));
    });
    const auto warm = waitForWarmUps(
        *c, [](const nlohmann::json& w) { return w["finished"] == 11 && !w["running"].get<bool>(); });
    EXPECT_EQ(warm["started"], 11) << warm.dump();
    const std::size_t fitsBefore = bodyJson(c->Get("/api/stats"))["fits"].size();
    EXPECT_EQ(postFit(*c, MRI_BRAIN, epsText(*draft))["state"], "done") << "not a cache hit";
    EXPECT_EQ(bodyJson(c->Get("/api/stats"))["fits"].size(), fitsBefore);
}

TEST(ServerWarmUp, ANewJobCancelsARunningWarmUp) {
    ServerWorld world;
    // Uniform noise: at eps = a half of the range the fit needs many small boxes, so the warm-up (the
    // first at the step below, 47 % of the range) runs long enough to be caught.
    std::mt19937 random(7);
    std::string noise = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\nencoding: raw\n\n";
    for (int i = 0; i < 64 * 64 * 64; ++i)
        noise.push_back(static_cast<char>(random() & 0xff));
    world.dir().write("data/noise.nrrd", noise);
    LoopbackServer server(warmingOptions(world));
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
    options.warmUpFits = false; // what this test is about, so not left to quietOptions()
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
