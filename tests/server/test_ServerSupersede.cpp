// A newer frame from one client supersedes its frame still waiting for the render thread, held busy here.
#include "HoldingRanks.h"
#include "ServerFixture.h"

#include <chrono>
#include <future>
#include <string>
#include <thread>
#include <vector>

namespace vots::test {
namespace {

TEST(ServerSupersede, NewerFrameFromSameClientSupersedesWaitingOne) {
    ServerWorld world;
    auto options = world.options();
    auto ranks = std::make_shared<HoldingRanks>();
    options.ranks = ranks;
    options.warmUpFits = false;
    LoopbackServer server(options);
    const ReleaseOnExit releaseOnExit{*ranks};
    const auto get = [&server](const std::string& target) { return server.client()->Get(target.c_str()); };
    const std::string frame = std::string("/render?dataset=") + BLOBS + "&eps=5%25";

    // The render thread takes the first frame and stays in it until released.
    auto busy = std::async(std::launch::async, get, frame + "&size=48x48&client=busy");
    ASSERT_TRUE(ranks->waitUntilHolding());
    auto older = std::async(std::launch::async, get, frame + "&size=32x32&cam=az=10&client=viewer");
    bool queued = false; // the older frame waits behind the held one: nothing else can take it
    for (int i = 0; i < 3000 && !queued; ++i) {
        queued = bodyJson(server.client()->Get("/api/stats"))["renderer"]["waiting"].get<int>() == 1;
        if (!queued) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_TRUE(queued) << "the older frame never queued";
    auto newer = std::async(std::launch::async, get, frame + "&size=40x40&cam=az=20&client=viewer");

    // Answered while the render thread is still held: the newer frame replaced it in the queue.
    const auto oldRes = older.get();
    ASSERT_TRUE(oldRes);
    EXPECT_EQ(oldRes->status, 409);
    EXPECT_EQ(bodyJson(oldRes)["error"], "superseded");
    EXPECT_EQ(ranks->drawnWidths(), std::vector<int>{48});

    ranks->release();
    const auto newRes = newer.get();
    const auto busyRes = busy.get();
    ASSERT_TRUE(newRes && busyRes);
    EXPECT_EQ(busyRes->status, 200) << busyRes->body;
    EXPECT_EQ(newRes->status, 200) << newRes->body;
    EXPECT_EQ(ranks->drawnWidths(), (std::vector<int>{48, 40})) << "the superseded frame was drawn";
    EXPECT_EQ(bodyJson(server.client()->Get("/api/stats"))["frames"]["superseded"].get<int>(), 1);
}

} // namespace
} // namespace vots::test
