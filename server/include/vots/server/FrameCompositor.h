// The hook through which the render thread has a frame drawn on other processes too and composited with
// its own (`vots serve` under mpirun); the server knows nothing of how the others are reached.
#pragma once

#include "vots/render/FrameRequest.h"
#include "vots/render/Image.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vots::render {
class GridRenderer;
class VotRenderer;
} // namespace vots::render

namespace vots::server {

/// One frame of a dataset, as every rank draws its part of it: from the Vots of its slab fitted at `eps`,
/// from its slab's samples (frame.renderer == Grid; eps and degree unused), or from its slab's Vots of a
/// `.vots` file (votsFile; the window is then the union of the ranks' Vot values, as one process takes
/// the whole Vot-Space's).
struct CompositeRequest {
    render::FrameRequest frame;
    std::string dataset;
    std::filesystem::path volumePath;          // the volume, or the .vots file: the same path on every rank
    std::array<float, 2> valueRange{0.f, 0.f}; // the whole volume's min and max sample
    float eps = 0.f;                           // data units
    int degree = 3;
    bool votsFile = false;
    /// When set, this process's slab fit (if the frame fits) reports its progress through it, standing
    /// for every rank's, as `mpirun vots fit --progress` does: the fit job's progress in the viewer.
    std::function<void(double fraction, const char* stage)> fitProgress;
};

/// One rank's part of the last composited frame.
struct RankTimes {
    int rank = 0;
    double fitMs = 0.0;         // fitting its slab for this frame (0 when it held the fit already)
    double frameMs = 0.0;       // drawing its float frame
    double compositeMs = 0.0;   // on rank 0, from the end of its own frame until this rank's was combined
    std::uint64_t votCount = 0; // Vots of the rank's slab fit the frame was drawn from (0 for the grid)
    double heldFitMs = 0.0;     // what the fit the frame was drawn from took, whenever it was made
};

/// What the server knows of a volume dataset's samples when they stay with the ranks, each of which reads
/// its own slab: no process holds the whole volume.
struct VolumeSummary {
    std::array<float, 2> range{0.f, 0.f}; // the whole volume's min and max sample
    std::uint32_t contentCrc = 0;         // fit::Volume::contentCrc of the whole, chained from the ranks'
};

/// Thrown by draw() or summarize() when a rank's slab would need more memory than its --memory-budget
/// leaves: answered 507, as a study over the one-process budget is, before the rank reads it.
class RanksOverBudget : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Thrown by draw() when a rank no longer answers: the frame and every later one are refused (503).
class RanksLost : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class FrameCompositor {
public:
    virtual ~FrameCompositor() = default;
    /// Processes drawing each frame, this one included.
    virtual int ranks() const = 0;
    /// Empty when draw() can take this frame of the dataset; else why not (the server answers 409).
    virtual std::string refusal(const std::string& dataset, const render::FrameRequest& frame) const = 0;
    /// On the render thread, its GL context current: draws the frame on every rank (this one's part with
    /// `vots` or `grid`, which it may upload to) and returns the displayed image. Throws RanksLost, or
    /// fit::InputError / std::runtime_error for what a rank could not draw.
    virtual render::RgbaImage draw(const CompositeRequest& request, render::VotRenderer& vots,
                                   render::GridRenderer& grid) = 0;
    /// Any thread, exclusive with draw(): every rank reads its slab of the volume file and gives its part of
    /// the summary, which is returned. Throws as draw() does.
    virtual VolumeSummary summarize(const std::filesystem::path& volumePath) = 0;
    /// The last composited frame's times, in rank order; empty before the first. Thread-safe.
    virtual std::vector<RankTimes> lastTimes() const = 0;
};

} // namespace vots::server
