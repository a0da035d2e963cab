// ServerStats' render activity, which warm-up fits wait on: a frame in flight or just ended counts, also
// one that ended by an exception.
#include "vots/server/ServerStats.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

namespace vots::server {
namespace {

using namespace std::chrono_literals;

TEST(ServerStats, RenderActivityCoversFramesInFlightAndAQuietTimeAfter) {
    ServerStats stats;
    EXPECT_FALSE(stats.renderedWithin(50ms)) << "no frame yet";
    {
        const FrameMark mark(stats);
        std::this_thread::sleep_for(80ms);
        EXPECT_TRUE(stats.renderedWithin(50ms)) << "a frame longer than the quiet time is still in flight";
    }
    EXPECT_TRUE(stats.renderedWithin(50ms));
    std::this_thread::sleep_for(80ms);
    EXPECT_FALSE(stats.renderedWithin(50ms));
    try {
        const FrameMark mark(stats);
        throw std::runtime_error("upload failed");
    } catch (const std::runtime_error&) {
    }
    std::this_thread::sleep_for(80ms);
    EXPECT_FALSE(stats.renderedWithin(50ms)) << "a failed frame must not leave the renderer busy for ever";
}

} // namespace
} // namespace vots::server
