// A newer frame from one client supersedes its frame still waiting for the render thread, held busy here.
#include "ServerFixture.h"

#include "vots/dist/FrameRanks.h"

#include <chrono>
#include <condition_variable>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vots::test {
namespace {

/// Draws flat frames through the ranks' port, so that the test decides when the render thread is free:
/// the first frame holds it until release(). Records the width of every frame it drew.
class HoldingRanks : public dist::FrameRanks {
public:
    int ranks() const override { return 1; }
    std::string refusal(const std::string&, const render::FrameRequest&) const override { return ""; }
    dist::ComposedFrame draw(const dist::DrawRequest& request, render::VotRenderer&,
                             render::GridRenderer&) override {
        std::unique_lock lock(mMutex);
        mDrawnWidths.push_back(request.frame.width);
        if (mDrawnWidths.size() == 1) {
            mHolding = true;
            mChanged.notify_all();
            mChanged.wait(lock, [this] { return mReleased; });
        }
        const std::size_t pixels = static_cast<std::size_t>(request.frame.width * request.frame.height);
        return {{request.frame.width, request.frame.height, std::vector<float>(pixels, 255.f)}, {0.f, 255.f}};
    }
    dist::RanksFit fit(const dist::FitRequest&, const dist::FitProgress&) override { return {1, 0.0}; }
    dist::VolumeSummary summarize(const std::filesystem::path&, int) override { return {{0.f, 255.f}, 1u}; }
    std::vector<dist::RankTimes> lastTimes() const override { return {}; }

    /// Waits (a minute at most) until the render thread is inside the first frame.
    bool waitUntilHolding() {
        std::unique_lock lock(mMutex);
        return mChanged.wait_for(lock, std::chrono::minutes(1), [this] { return mHolding; });
    }
    void release() {
        std::lock_guard lock(mMutex);
        mReleased = true;
        mChanged.notify_all();
    }
    std::vector<int> drawnWidths() {
        std::lock_guard lock(mMutex);
        return mDrawnWidths;
    }

private:
    std::mutex mMutex;
    std::condition_variable mChanged;
    bool mHolding = false;
    bool mReleased = false;
    std::vector<int> mDrawnWidths;
};

/// Releases the held frame however the test ends, so that the server can stop.
struct ReleaseOnExit {
    HoldingRanks& ranks;
    ~ReleaseOnExit() { ranks.release(); }
};

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
