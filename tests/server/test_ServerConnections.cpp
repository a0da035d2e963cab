// Hostile connections on a loopback server: idle sockets and event-stream watchers cost no worker, so a
// plain request is answered at once; one client flooding renders or fits gets 429, another is served;
// a stop however early ends listening.
#include "NoiseVolume.h"
#include "RawClient.h"
#include "ServerFixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace vots::test {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

std::string slowFitBody(double eps) {
    return std::string(R"({"dataset":")") + NOISE + R"(","eps":)" + std::to_string(eps) + "}";
}

struct OpenSockets {
    std::vector<int> fds;
    ~OpenSockets() {
        for (const int fd : fds)
            ::close(fd);
    }
};

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

TEST(ServerConnections, IdleConnectionsAndWatchersDoNotDelayAPlainRequest) {
    ServerWorld world;
    addNoiseVolume(world);
    auto options = world.quietOptions();
    options.maxRunningFits = 1;
    LoopbackServer server(options);
    const int port = server.port();
    auto c = server.client();
    const auto posted = c->Post("/api/fit", slowFitBody(0.02), "application/json");
    ASSERT_TRUE(posted);
    ASSERT_EQ(posted->status, 202) << posted->body;
    const std::string events = "/api/jobs/" + std::to_string(bodyJson(posted)["job"].get<int>()) + "/events";

    constexpr int IDLE = 100;
    constexpr int WATCHERS = 20; // more than the 12 workers: before the gate they held every one
    OpenSockets idle, watchers;
    for (int i = 0; i < IDLE; ++i) {
        idle.fds.push_back(connectFrom("127.0.0.1", port));
        ASSERT_GE(idle.fds.back(), 0);
    }
    for (int i = 0; i < WATCHERS; ++i) {
        const int fd = connectFrom("127.0.0.1", port);
        ASSERT_GE(fd, 0);
        watchers.fds.push_back(fd);
        ASSERT_TRUE(sendAll(fd, requestText("GET", events, port)));
        const std::string start = receive(fd, std::chrono::seconds(10), 12);
        ASSERT_EQ(start.substr(0, 12), "HTTP/1.1 200") << "watcher " << i;
    }

    const auto stats = bodyJson(c->Get("/api/stats"));
    ASSERT_EQ(stats["fitJobs"]["active"], 1) << "the fit ended before the test could measure";
    EXPECT_EQ(stats["connections"]["eventStreams"], WATCHERS);
    EXPECT_GE(stats["connections"]["waiting"].get<int>(), IDLE);

    for (int i = 0; i < 5; ++i) {
        const auto start = Clock::now();
        const auto res = server.client()->Get("/api/datasets");
        const double seconds = secondsSince(start);
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 200);
        EXPECT_LT(seconds, 1.0) << "a plain request waited behind the idle connections and watchers";
    }
}

TEST(ServerConnections, AClientFloodingFitsGets429AndAnotherIsServed) {
    ServerWorld world;
    addNoiseVolume(world);
    auto options = world.options();
    options.maxRunningFits = 1;
    options.maxQueuedFits = 8;
    options.maxFitsPerClient = 3;
    LoopbackServer server(options);
    const int port = server.port();

    // The first fit runs for seconds and the others queue behind it: all three stay active.
    for (const double eps : {0.02, 0.03, 0.04}) {
        const RawAnswer accepted =
            exchangeFrom("127.0.0.2", port, requestText("POST", "/api/fit", port, slowFitBody(eps)));
        ASSERT_EQ(accepted.status, 202) << accepted.body;
    }
    const RawAnswer flood =
        exchangeFrom("127.0.0.2", port, requestText("POST", "/api/fit", port, slowFitBody(0.05)));
    EXPECT_EQ(flood.status, 429);
    EXPECT_NE(flood.headers.find("Content-Type: application/json"), std::string::npos);
    const auto error = nlohmann::json::parse(flood.body, nullptr, false);
    ASSERT_TRUE(error.is_object()) << flood.body;
    EXPECT_NE(error["error"].get<std::string>().find("per client"), std::string::npos);

    // Joining a fit already active costs no place: the flooder may still ask for one it has started.
    EXPECT_EQ(
        exchangeFrom("127.0.0.2", port, requestText("POST", "/api/fit", port, slowFitBody(0.03))).status,
        202);
    const RawAnswer other =
        exchangeFrom("127.0.0.3", port, requestText("POST", "/api/fit", port, slowFitBody(0.05)));
    EXPECT_EQ(other.status, 202) << other.body;
}

TEST(ServerConnections, AClientFloodingRendersGets429AndAnotherIsServed) {
    ServerWorld world;
    addNoiseVolume(world);
    auto options = world.options();
    options.maxRunningFits = 1;
    options.maxRendersPerClient = 2;
    options.warmUpFits = false;
    LoopbackServer server(options);
    const int port = server.port();
    auto c = server.client();
    ASSERT_TRUE(bodyJson(c->Get("/api/stats"))["renderer"]["available"].get<bool>())
        << "no EGL context (Mesa's llvmpipe gives one without a GPU)";

    // Two renders that wait for a slow fit hold both of 127.0.0.2's places, and two more wait their turn.
    const std::string waiting = std::string("/render?dataset=") + NOISE + "&size=64x64&eps=0.02";
    OpenSockets held;
    for (int i = 0; i < 4; ++i) {
        held.fds.push_back(connectFrom("127.0.0.2", port));
        ASSERT_TRUE(sendAll(held.fds.back(), requestText("GET", waiting, port)));
    }
    waitForStats(*c, [](const nlohmann::json& s) {
        return s["fitJobs"]["active"] == 1 && s["connections"]["waiting"] == 0;
    });
    std::this_thread::sleep_for(milliseconds(300)); // the four handlers past their first line

    const auto start = Clock::now();
    const RawAnswer flood = exchangeFrom("127.0.0.2", port, requestText("GET", waiting, port));
    EXPECT_LT(secondsSince(start), 1.0);
    EXPECT_EQ(flood.status, 429);
    const auto error = nlohmann::json::parse(flood.body, nullptr, false);
    ASSERT_TRUE(error.is_object()) << flood.body;
    EXPECT_TRUE(error["error"].is_string());

    // A reference frame needs no fit: 127.0.0.3 is drawn while 127.0.0.2's renders still wait.
    const RawAnswer other = exchangeFrom(
        "127.0.0.3", port,
        requestText("GET", std::string("/render?dataset=") + BLOBS + "&size=64x64&mode=reference", port));
    EXPECT_EQ(other.status, 200) << other.body.substr(0, 200);
    EXPECT_EQ(bodyJson(c->Get("/api/stats"))["fitJobs"]["active"], 1) << "the held renders were not waiting";
}

/// Listens on a thread; true when that listening ended within `limit` (else stops it again once it runs,
/// so that a failing test still ends).
bool listeningEndsAfterStop(server::Server& srv, std::chrono::seconds limit) {
    std::promise<void> ended;
    auto endedFuture = ended.get_future();
    std::thread listener([&] {
        srv.listenAfterBind();
        ended.set_value();
    });
    srv.stop(); // at once: listening has most likely not begun yet
    const bool inTime = endedFuture.wait_for(limit) == std::future_status::ready;
    while (!inTime && endedFuture.wait_for(milliseconds(10)) != std::future_status::ready)
        srv.stop();
    listener.join();
    return inTime;
}

TEST(ServerConnections, AStopThatComesBeforeListeningBeginsStillEndsIt) {
    ServerWorld world;
    auto options = world.options();
    options.withRenderer = false;
    // The stop's race with the listening thread's start is lost only now and then: try it many times.
    for (int attempt = 0; attempt < 40; ++attempt) {
        server::Server srv(options);
        ASSERT_GT(srv.bindToAnyPort("127.0.0.1"), 0);
        ASSERT_TRUE(listeningEndsAfterStop(srv, std::chrono::seconds(20))) << "attempt " << attempt;
    }
    server::Server stopped(options);
    ASSERT_GT(stopped.bindToAnyPort("127.0.0.1"), 0);
    stopped.stop();
    EXPECT_FALSE(stopped.listenAfterBind()) << "listening began after stop()";
}

} // namespace
} // namespace vots::test
