// Reading a drawn frame out of its float target, timed into its stats.
#pragma once

#include "FloatTarget.h"

#include "vots/render/FrameStats.h"
#include "vots/render/Image.h"

#include <chrono>

namespace vots::render {

using FrameClock = std::chrono::steady_clock;

/// Milliseconds since t0, for the FrameStats timings.
inline double msSince(FrameClock::time_point t0) {
    return std::chrono::duration<double, std::milli>(FrameClock::now() - t0).count();
}

/// The frame's values, top row first; the time the readback took goes to stats.readbackMs.
FloatImage readFloatFrame(const FloatTarget& target, FrameStats& stats);

} // namespace vots::render
