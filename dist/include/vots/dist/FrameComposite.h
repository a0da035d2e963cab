// The composite of the ranks' float frames one rank at a time, for `vots serve` under mpirun: each rank's
// frame is combined as it arrives, so a rank that never answers leaves nothing waiting.
#pragma once

#include "vots/dist/CompositeOp.h"

#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"

#include <array>
#include <optional>
#include <vector>

namespace vots::dist {

/// What one rank drew: the projection's float frame, and for the Vots' aip the ray lengths in its cells.
/// The grid's parts need no lengths: each is drawn with the whole ray's (GridRenderer::uploadPlanes).
struct RankFrame {
    render::FloatImage frame;
    std::optional<render::FloatImage> lengths;
    RankSource source = RankSource::Vots;
    /// The range this rank's part is shown over when the window is the ranks' union, as under `mpirun vots
    /// render`: the density's box sizes (VotRenderer::densityRange), or the values of a .vots file's Vots
    /// (VotRenderer::valueRange); nullopt when the window is the volume's.
    std::optional<std::array<float, 2>> displayRange;
};

/// The ranks' frames combined by compositeOpFor's operation, with the arithmetic of the collective
/// composite (the same functions, so both give the same bits). Where the ranks give display ranges (the
/// density, a .vots file) the frame is shown over their union.
class FrameComposite {
public:
    /// Starts from one rank's frame; throws std::logic_error for a density frame without its range, or an
    /// aip frame of the Vots without its lengths.
    FrameComposite(render::RenderMode mode, RankFrame first);
    /// Adds another rank's frame; throws std::runtime_error when it does not match the first.
    void add(const RankFrame& other);
    /// The composited frame; the composite is spent.
    render::FloatImage finish();
    /// The union of the frames' display ranges; nullopt when they gave none (the window is the volume's).
    std::optional<std::array<float, 2>> displayRange() const { return mDisplayRange; }

private:
    CompositeOp mOp;
    RankSource mSource;
    render::FloatImage mFrame; // Max, Min, MinOfCutRays (in its combining form): the running extreme
    std::vector<double> mSums; // WeightedMean: the integrals, then the lengths; Sum: the sums
    std::optional<std::array<float, 2>> mDisplayRange;
};

} // namespace vots::dist
