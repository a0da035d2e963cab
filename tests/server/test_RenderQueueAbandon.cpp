// The render thread gives up a viewer's still between the bands of its walk when that viewer asks for
// another frame, and only then: not a frame that may not be given up, not for another client's frame.
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

using test::frameOf;

int statusOf(RenderQueue& queue, RenderJob job) {
    try {
        (void)queue.render(std::move(job));
        return 200;
    } catch (const HttpError& e) {
        return e.status();
    }
}

class RenderQueueAbandon : public ::testing::Test {
protected:
    // The fragment walk, which draws in bands, on any machine (a GPU's compute walk draws a frame whole).
    void SetUp() override {
        ::setenv("VOTS_WALK_SHADER", "fragment", 1);
        queue = std::make_unique<RenderQueue>(stats, foreground);
        ASSERT_TRUE(queue->hasContext()) << queue->contextError();
    }
    void TearDown() override {
        queue.reset();
        ::unsetenv("VOTS_WALK_SHADER");
    }

    // Draws `first` (a large frame) and sends `second` while the render thread draws it; the first's status.
    // nullopt when the first ended before the second could be sent (a machine that draws it at once).
    std::optional<int> whileDrawing(const RenderJob& first, const RenderJob& second) {
        auto drawn = std::async(std::launch::async, [&] { return statusOf(*queue, first); });
        while (!foreground.renderedWithin(std::chrono::milliseconds(0)) &&
               drawn.wait_for(std::chrono::milliseconds(1)) != std::future_status::ready) {
        }
        if (drawn.wait_for(std::chrono::seconds(0)) == std::future_status::ready) return std::nullopt;
        EXPECT_EQ(statusOf(*queue, second), 200);
        return drawn.get();
    }

    ServerStats stats;
    ForegroundActivity foreground;
    std::unique_ptr<RenderQueue> queue;
};

TEST_F(RenderQueueAbandon, TheClientsNextFrameGivesUpItsStillBeingDrawn) {
    std::optional<int> first;
    for (int attempt = 0; attempt < 5 && !first; ++attempt)
        first = whileDrawing(frameOf("viewer", 2048, true), frameOf("viewer", 64, false));
    ASSERT_TRUE(first) << "the 2048^2 frame was never still being drawn when the next one came";
    EXPECT_EQ(*first, 409);
    EXPECT_EQ(stats.frames().superseded, 1u);
}

TEST_F(RenderQueueAbandon, AFrameNotAbandonableOrAnotherClientsNextFrameDoesNot) {
    for (const auto& [first, second] :
         {std::pair{frameOf("viewer", 2048, false), frameOf("viewer", 64, false)},
          std::pair{frameOf("viewer", 2048, true), frameOf("other", 64, false)}}) {
        std::optional<int> status;
        for (int attempt = 0; attempt < 5 && !status; ++attempt)
            status = whileDrawing(first, second);
        ASSERT_TRUE(status);
        EXPECT_EQ(*status, 200);
    }
    EXPECT_EQ(stats.frames().superseded, 0u);
}

} // namespace
} // namespace vots::server
