// A viewer wants one fit at a time: its newer fit cancels the older one, unless somebody else wants it too.
#include "NoiseVolume.h"
#include "RawClient.h"
#include "ServerFixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <string>
#include <thread>

namespace vots::test {
namespace {

using Clock = std::chrono::steady_clock;

/// A fit of the noise volume (seconds at these eps), from the viewer `client` when it is not empty.
std::string fitBody(double eps, const std::string& client = {}) {
    std::string body = std::string(R"({"dataset":")") + NOISE + R"(","eps":)" + std::to_string(eps);
    if (!client.empty()) body += R"(,"client":")" + client + "\"";
    return body + "}";
}

class FitSupersede : public ::testing::Test {
protected:
    FitSupersede() {
        addNoiseVolume(mWorld);
        auto options = mWorld.quietOptions();
        options.maxRunningFits = 1; // the second fit queues behind the first
        mServer = std::make_unique<LoopbackServer>(options);
    }

    /// Starts a fit from the address `source`; the job JSON (a test failure unless 202).
    nlohmann::json post(const std::string& source, const std::string& body) {
        const int port = mServer->port();
        const RawAnswer answer = exchangeFrom(source, port, requestText("POST", "/api/fit", port, body));
        EXPECT_EQ(answer.status, 202) << answer.body;
        return nlohmann::json::parse(answer.body, nullptr, false);
    }

    nlohmann::json job(const nlohmann::json& started) {
        return bodyJson(mServer->client()->Get("/api/jobs/" + std::to_string(started["job"].get<int>())));
    }

    /// The job once it has ended (done or failed), or as it is after a minute.
    nlohmann::json ended(const nlohmann::json& started) {
        const auto deadline = Clock::now() + std::chrono::minutes(1);
        nlohmann::json now = job(started);
        while (now["state"] != "done" && now["state"] != "failed" && Clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
            now = job(started);
        }
        return now;
    }

    int activeFits() {
        return bodyJson(mServer->client()->Get("/api/stats"))["fitJobs"]["active"].get<int>();
    }

    ServerWorld mWorld;
    std::unique_ptr<LoopbackServer> mServer;
};

bool superseded(const nlohmann::json& job) {
    return job["state"] == "failed" && job["error"].is_string() &&
           job["error"].get<std::string>().find("superseded") != std::string::npos;
}

TEST_F(FitSupersede, ANewerFitFromTheSameViewerCancelsTheRunningAndTheQueuedOne) {
    const auto running = post("127.0.0.2", fitBody(0.02, "tab1"));
    const auto queued = post("127.0.0.2", fitBody(0.03, "tab1"));
    // The running fit takes seconds: it fails as superseded only if it was stopped.
    const auto runningEnd = ended(running);
    EXPECT_TRUE(superseded(runningEnd)) << runningEnd.dump();

    // Queued, or running in the freed worker: either way it is stopped.
    const auto newest = post("127.0.0.2", fitBody(0.04, "tab1"));
    EXPECT_TRUE(superseded(ended(queued)));
    EXPECT_NE(job(newest)["state"], "failed");
    EXPECT_EQ(activeFits(), 1) << "only the newest fit is left";
    // The same eps again is the same job, still wanted.
    EXPECT_EQ(post("127.0.0.2", fitBody(0.04, "tab1"))["job"], newest["job"]);
    EXPECT_NE(job(newest)["state"], "failed");
}

TEST_F(FitSupersede, AFitThatSomebodyElseWantsGoesOn) {
    const auto shared = post("127.0.0.2", fitBody(0.02, "tab1"));
    // Joined by a request without a viewer (a script), by another viewer, and the same id from another
    // address (which is another viewer: an id counts per address).
    EXPECT_EQ(post("127.0.0.2", fitBody(0.02))["job"], shared["job"]);
    const auto other = post("127.0.0.3", fitBody(0.02, "tab2"));
    EXPECT_EQ(other["job"], shared["job"]);
    EXPECT_EQ(post("127.0.0.4", fitBody(0.02, "tab1"))["job"], shared["job"]);

    post("127.0.0.2", fitBody(0.03, "tab1"));
    post("127.0.0.3", fitBody(0.03, "tab2"));
    post("127.0.0.4", fitBody(0.03, "tab1"));
    // A cancelled fit fails within milliseconds; this one is still wanted by the script.
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    EXPECT_EQ(job(shared)["state"], "running");
    EXPECT_EQ(activeFits(), 2);
}

TEST_F(FitSupersede, AViewerCannotWithdrawAnotherAddressFromItsFit) {
    const auto mine = post("127.0.0.2", fitBody(0.02, "tab1"));
    post("127.0.0.3", fitBody(0.03, "tab1")); // the same id from elsewhere
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    EXPECT_EQ(job(mine)["state"], "running");
}

TEST_F(FitSupersede, ANewJobForTheKeyOfACancelledOneStartsAfresh) {
    const auto first = post("127.0.0.2", fitBody(0.02, "tab1"));
    post("127.0.0.2", fitBody(0.03, "tab1"));
    const auto again = post("127.0.0.2", fitBody(0.02, "tab1"));
    EXPECT_NE(again["job"], first["job"]) << "joined a cancelled job";
    EXPECT_TRUE(superseded(ended(first)));
    EXPECT_NE(job(again)["state"], "failed");
}

} // namespace
} // namespace vots::test
