// A client's newer frame takes its waiting frame's place in the render queue instead of going to the back,
// so a viewer that replaces its frame often (a paused drag's still, then a draft) is still drawn in turn.
#include "HttpError.h"
#include "RenderQueueJobs.h"
#include "ServerStats.h"
#include "frames/ForegroundActivity.h"
#include "frames/RenderQueue.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <future>
#include <optional>
#include <thread>

namespace vots::server {
namespace {

using Clock = std::chrono::steady_clock;
using test::frameOf;

// When the render queue answered the job: the time, or nullopt for a refusal (its status in `status`).
struct Answer {
    std::optional<Clock::time_point> at;
    int status = 200;
};

Answer answerOf(RenderQueue& queue, RenderJob job) {
    try {
        (void)queue.render(std::move(job));
        return {Clock::now(), 200};
    } catch (const HttpError& e) {
        return {std::nullopt, e.status()};
    }
}

// Waits until `count` jobs wait in the queue (the render thread busy with another), at most 10 s.
bool waitForWaiting(const RenderQueue& queue, std::size_t count) {
    const auto until = Clock::now() + std::chrono::seconds(10);
    while (queue.waiting() != count) {
        if (Clock::now() > until) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return true;
}

TEST(RenderQueueReplace, ANewerFrameOfAClientIsDrawnInItsWaitingFramesTurn) {
    // The fragment walk: slow enough on any machine for the 2048^2 frame to outlast the queueing below.
    ::setenv("VOTS_WALK_SHADER", "fragment", 1);
    ServerStats stats;
    ForegroundActivity foreground;
    RenderQueue queue(stats, foreground);
    ::unsetenv("VOTS_WALK_SHADER"); // read when the render thread starts, which the constructor waits for
    ASSERT_TRUE(queue.hasContext()) << queue.contextError();

    // A large frame keeps the render thread busy while three frames are queued behind it.
    auto busy = std::async(std::launch::async, [&] { return answerOf(queue, frameOf("busy", 2048)); });
    while (!foreground.renderedWithin(std::chrono::milliseconds(0)))
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    auto first = std::async(std::launch::async, [&] { return answerOf(queue, frameOf("a", 384)); });
    ASSERT_TRUE(waitForWaiting(queue, 1));
    auto other = std::async(std::launch::async, [&] { return answerOf(queue, frameOf("b", 384)); });
    ASSERT_TRUE(waitForWaiting(queue, 2));
    auto newer = std::async(std::launch::async, [&] { return answerOf(queue, frameOf("a", 384)); });

    const Answer replacedAnswer = first.get();
    EXPECT_EQ(replacedAnswer.status, 409); // superseded at once by the client's newer frame
    EXPECT_EQ(queue.waiting(), 2u) << "the newer frame replaced the waiting one; the queue did not grow";
    ASSERT_TRUE(busy.get().at) << "the busy frame was refused";
    const Answer newerAnswer = newer.get();
    const Answer otherAnswer = other.get();
    ASSERT_TRUE(newerAnswer.at && otherAnswer.at);
    // Client a's frame was queued before b's: its replacement is drawn first.
    EXPECT_LT(*newerAnswer.at, *otherAnswer.at);
}

} // namespace
} // namespace vots::server
