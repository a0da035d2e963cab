// MIP of a Vot-Space on the CPU's cores in object order: Vots by falling bound, each over its footprint.
#pragma once

#include "SplatKernel.h"

#include "vots/render/Camera.h"
#include "vots/render/CellDomain.h"
#include "vots/render/FrameStats.h"
#include "vots/render/GpuLayout.h"
#include "vots/render/Image.h"
#include "vots/render/Slab.h"

#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace vots::render {

/// Where no GPU is, the walk runs in llvmpipe's fragment shader: each ray steps through bricks and cells
/// with dependent reads, 8 divergent rays in lockstep. The splat turns the loop around: Vots in order of
/// falling upper bound, each over the pixels its box covers on screen, 8 neighbouring rays of one Vot at
/// a time (the same polynomial, no divergence, no lookups). A 16x16 tile whose every pixel already holds
/// at least a Vot's bound skips that Vot, and so does a pixel: after the bright Vots have been drawn most
/// Vots are skipped whole. The pixels are the walk's within float rounding: the max of each Vot along
/// each ray over its box grown by CLIP_SLACK, -inf where no Vot is met (bench/RESULTS.md compares them).
/// MIP only: the min and the mean need the background cells the walk sees.
class CpuSplat {
public:
    /// Copies the Vots and sorts them by falling bound, in levels kept in the order given: space order as
    /// VotRenderer keeps them (another order gives the same image, with runs a tile refuses less often).
    void upload(const std::vector<GpuVot>& vots);

    /// The MIP image (row 0 at the top, as readFloatFrame gives it), drawn by every core. Without
    /// culling every Vot is evaluated on every pixel of its footprint (for tests: the image is the
    /// same). `abandoned`, when set, is asked between runs of Vots: true throws FrameAbandoned.
    FloatImage draw(const CameraMatrices& matrices, const std::optional<SlabPlanes>& slab,
                    const std::optional<CellDomain>& domain, const std::array<int, 3>& cells, int width,
                    int height, bool culling, const std::function<bool()>& abandoned,
                    FrameStats& stats) const;

    /// What the frame reads of every Vot to place and cull it: 32 bytes, where the whole record (128) is
    /// read only for the Vots that reach a pixel.
    struct Placement {
        float centre[3];
        float half[3]; // half sides, CLIP_SLACK included
        float upper;
        float unused;
    };

private:
    // By falling upper bound in levels of LEVEL_VOTS, each level in space order (CpuSplat.cpp).
    std::vector<SplatVot> mVots;
    std::vector<Placement> mPlacements; // the same order
    std::vector<Placement> mRuns;       // per run of RUN_VOTS: the joint box and the largest bound
};

} // namespace vots::render
