// ForegroundActivity, which background work waits on: a frame (or, for cache files, a requested fit) in
// flight or just ended counts, also one that ended by an exception.
#include "frames/ForegroundActivity.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>

namespace vots::server {
namespace {

using namespace std::chrono_literals;

TEST(ForegroundActivity, RenderActivityCoversFramesInFlightAndAQuietTimeAfter) {
    ForegroundActivity stats;
    EXPECT_FALSE(stats.renderedWithin(50ms)) << "no frame yet";
    {
        const ForegroundMark mark(stats, Foreground::Frame);
        std::this_thread::sleep_for(80ms);
        EXPECT_TRUE(stats.renderedWithin(50ms)) << "a frame longer than the quiet time is still in flight";
    }
    EXPECT_TRUE(stats.renderedWithin(50ms));
    std::this_thread::sleep_for(80ms);
    EXPECT_FALSE(stats.renderedWithin(50ms));
    try {
        const ForegroundMark mark(stats, Foreground::Frame);
        throw std::runtime_error("upload failed");
    } catch (const std::runtime_error&) {
    }
    std::this_thread::sleep_for(80ms);
    EXPECT_FALSE(stats.renderedWithin(50ms)) << "a failed frame must not leave the renderer busy for ever";
}

TEST(ForegroundActivity, RequestedFitsKeepTheServerBusyButDoNotCountAsRendering) {
    ForegroundActivity stats;
    EXPECT_FALSE(stats.busyWithin(50ms));
    {
        const ForegroundMark mark(stats, Foreground::Fit);
        EXPECT_TRUE(stats.busyWithin(50ms)) << "cache files wait for a running fit";
        EXPECT_FALSE(stats.renderedWithin(50ms)) << "warm-ups are cancelled by fits, not paused";
    }
    EXPECT_TRUE(stats.busyWithin(50ms));
    std::this_thread::sleep_for(80ms);
    EXPECT_FALSE(stats.busyWithin(50ms));
    {
        const ForegroundMark mark(stats, Foreground::Frame);
        EXPECT_TRUE(stats.busyWithin(50ms)) << "and for a frame";
    }
}

} // namespace
} // namespace vots::server
