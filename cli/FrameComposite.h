// The composite of the ranks' float frames on rank 0 without collectives, for `vots serve` under mpirun:
// each rank's frame is combined as it arrives, so a rank that never answers leaves nothing waiting.
#pragma once

#include "SlabDrawer.h"

#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"

#include <array>
#include <optional>
#include <vector>

namespace vots::cli {

/// The arithmetic of compositeOnRoot / compositeMeansOnRoot (the same functions): max for mip, min for minip
/// (a rank's ray that takes nothing, -inf, never wins), per pixel sum(mean x length) / sum(length) for the
/// aip. Frames of the exact grid (SlabFrame::fromGrid) combine as compositeGridOnRoot's: max, min, sum.
/// The density is the min of the ranks' smallest boxes (+inf, no box, never wins). Where the ranks give
/// display ranges (SlabFrame::displayRange: the density, a .vots file) the frame is shown over their union.
class FrameComposite {
public:
    /// Starts from rank 0's frame; throws std::logic_error for a density frame without its range.
    FrameComposite(render::RenderMode mode, SlabFrame first);
    /// Adds another rank's frame; throws std::runtime_error when its size is not the first's.
    void add(const SlabFrame& other);
    /// The composited frame; the composite is spent.
    render::FloatImage finish();
    /// The union of the frames' display ranges; nullopt when they gave none (the window is the volume's).
    std::optional<std::array<float, 2>> displayRange() const { return mDisplayRange; }

private:
    render::RenderMode mMode;
    bool mFromGrid;
    render::FloatImage mFrame; // mip, minip (+inf for "nothing yet"): the running max / min
    std::vector<double> mSums; // aip: the integrals, then the lengths, of every pixel (the grid's: the sums)
    std::optional<std::array<float, 2>> mDisplayRange;
};

} // namespace vots::cli
