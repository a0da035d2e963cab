// Counters and timings of the last frame a renderer drew (for logs, the server's stats and bench).
#pragma once

#include <cstddef>

namespace vots::render {

struct FrameStats {
    std::size_t votsTotal = 0;  // Vots uploaded
    std::size_t votsDrawn = 0;  // instances submitted after CPU culling (Vot MIP, Raster); all for
                                // density; 0 for the Walk strategy (no instances)
    int batches = 0;            // draw calls this frame
    double gpuMs = 0.0;         // wall time from first draw to glFinish, ms (includes culling)
    double readbackMs = 0.0;    // glReadPixels of the result, ms
    double boundsAheadMs = 0.0; // Walk: the CPU's per-view bounds ahead (BrickAhead), ms; part of gpuMs
};

} // namespace vots::render
