// The port through which the server has frames drawn and fits made on every rank (`vots serve` under
// mpirun): it gets the composited float frame back and shows it as one process shows its own.
#pragma once

#include "vots/dist/Failure.h"
#include "vots/dist/RankPart.h"

#include "vots/render/FrameRequest.h"
#include "vots/render/Image.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace vots::dist { // render::GridRenderer and render::VotRenderer are declared by RankPart.h

/// A fit of a volume dataset on every rank, each of its cells, with the whole volume's options.
struct FitRequest {
    std::string dataset;
    std::filesystem::path volumePath;          // the same path on every rank
    int frame = 0;                             // the 3D volume of a 4D file (0-based); 0 for a 3D one
    std::array<float, 2> valueRange{0.f, 0.f}; // the whole volume's min and max sample
    float eps = 0.f;                           // data units
    int degree = 3;
    fit::FitNorm norm = fit::SERVE_FIT_NORM;
};

/// One frame of a dataset, as every rank draws its part of it: from the Vots of its cells fitted at
/// `fit.eps` (fitted first when they are not), from its cells' samples (frame.renderer == Grid; eps and
/// degree unused), or from its Vots of a `.vots` file (votsFile: fit.volumePath is the file's).
struct DrawRequest {
    render::FrameRequest frame;
    FitRequest fit;
    bool votsFile = false;
};

/// The frame of the whole: the composited float image and the range its display maps, the volume's or
/// the union of the ranks' (the density's box sizes, a .vots file's values), as one process's renderer
/// gives it (render::renderFrame).
struct ComposedFrame {
    render::FloatImage image;
    std::array<float, 2> displayRange{0.f, 0.f};
};

/// What a fit on the ranks gave: the Vots of all their cells and the slowest rank's seconds. The
/// Vot-Space itself stays with the ranks.
struct RanksFit {
    std::uint64_t votCount = 0;
    double seconds = 0.0;
};

/// One rank's part of the last composited frame.
struct RankTimes {
    int rank = 0;
    double fitMs = 0.0;         // fitting its cells (or reading its planes, a .vots file) for this frame
    double frameMs = 0.0;       // drawing its float frame, after uploading a new fit
    double compositeMs = 0.0;   // on rank 0, from the end of its own frame until this rank's was combined
    std::uint64_t votCount = 0; // Vots of the rank's fit the frame was drawn from (0 for the grid)
    double heldFitMs = 0.0;     // what the fit the frame was drawn from took, whenever it was made
};

/// What the server knows of a volume dataset's samples when they stay with the ranks, each of which reads
/// its own cells' planes: no process holds the whole volume.
struct VolumeSummary {
    std::array<float, 2> range{0.f, 0.f}; // the whole volume's min and max sample
    std::uint32_t contentCrc = 0;         // fit::Volume::contentCrc of the whole, chained from the ranks'
};

/// Every method may throw RanksLost (a rank no longer answers), RanksOverBudget (a rank's planes exceed
/// its memory budget), fit::InputError (what a rank was given is bad input) or std::runtime_error.
class FrameRanks {
public:
    virtual ~FrameRanks() = default;
    /// Processes drawing each frame, this one included.
    virtual int ranks() const = 0;
    /// Empty when the ranks can draw this frame of the dataset; else why not (the server answers 409).
    virtual std::string refusal(const std::string& dataset, const render::FrameRequest& frame) const = 0;
    /// On the render thread, its GL context current: draws the frame on every rank (this one's part with
    /// `vots` or `grid`, which it may upload to) and returns it composited.
    virtual ComposedFrame draw(const DrawRequest& request, render::VotRenderer& vots,
                               render::GridRenderer& grid) = 0;
    /// Any thread, exclusive with draw(): every rank fits its cells, and holds the fit for the frames that
    /// follow; this process's fit reports through `progress` (when set), standing for every rank's.
    virtual RanksFit fit(const FitRequest& request, const FitProgress& progress) = 0;
    /// Any thread, exclusive with draw(): every rank reads its planes of the volume file's `frame` and
    /// gives its part of the summary, which is returned.
    virtual VolumeSummary summarize(const std::filesystem::path& volumePath, int frame) = 0;
    /// The last composited frame's times, in rank order; empty before the first. Thread-safe.
    virtual std::vector<RankTimes> lastTimes() const = 0;
};

} // namespace vots::dist
