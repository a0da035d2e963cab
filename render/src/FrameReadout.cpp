// Reading a drawn frame out of its float target, timed into its stats.
#include "FrameReadout.h"

namespace vots::render {

FloatImage readFloatFrame(const FloatTarget& target, FrameStats& stats) {
    const auto t0 = FrameClock::now();
    FloatImage image = target.readback();
    stats.readbackMs = msSince(t0);
    return image;
}

} // namespace vots::render
