// One rank's part of a served frame: the fit of its z slab at the requested eps (or the slab's samples
// for the exact grid), and its float frame.
#pragma once

#include "ZSlab.h"

#include "vots/fit/Fitter.h"

#include "vots/render/FrameRequest.h"
#include "vots/render/Image.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

namespace vots::render {
class GridRenderer;
class VotRenderer;
} // namespace vots::render

namespace vots::cli {

/// What one rank drew: the projection's float frame, and for the Vots' aip the ray lengths in its slab.
/// The grid's parts need no lengths: each is drawn with the whole ray's (GridRenderer::uploadSlab).
struct SlabFrame {
    render::FloatImage frame;
    std::optional<render::FloatImage> lengths;
    bool fromGrid = false;
    /// The range this rank's part is shown over when the window is the ranks' union, as under `mpirun vots
    /// render`: the density's box sizes (VotRenderer::densityRange), or the values of a .vots file's Vots
    /// (VotRenderer::valueRange); nullopt when the window is the volume's.
    std::optional<std::array<float, 2>> displayRange;
};

/// One rank's reading of its slab of a volume. Each plane is owned by one rank (a slab's cells' first
/// planes, and the last plane by the slab that ends there), so chaining the ranks' `crc` in rank order from
/// `gridCrc` with fit::combineCrc gives the volume's fit::Volume::contentCrc.
struct SlabSummary {
    std::array<float, 2> range{0.f, 0.f}; // min and max sample of the slab's planes
    std::uint32_t gridCrc = 0;            // of the whole volume's grid, the same on every rank
    std::uint32_t crc = 0;                // of the planes this rank owns, as floats
    std::uint64_t bytes = 0;              // their bytes as floats
};

/// The fit of a volume's slab as `mpirun vots render VOLUME --eps` makes it (automatic background, cells
/// certified), kept while the volume, eps and degree stay the same; or the slab's Vots of a .vots file.
/// The slab's samples are read once and kept, with a box cache per degree, as one process keeps a study's:
/// a refit at a new eps reuses the boxes fitted before.
class SlabDrawer {
public:
    /// `memoryBudget`: the --memory-budget text (empty: the default), which every read of a slab is
    /// checked against first (server::RanksOverBudget).
    SlabDrawer(int rank, int ranks, std::string memoryBudget)
        : mRank(rank), mRanks(ranks), mMemoryBudget(std::move(memoryBudget)) {}
    /// fit::FitOptions::progress.
    using Progress = std::function<void(double fraction, const char* stage)>;
    /// Reads and fits this rank's planes when they differ from the last call, and uploads the Vots to
    /// `vots`; returns the milliseconds it took (0 when it held the fit). `range` is the whole volume's;
    /// the fit reports through `progress` when it is set.
    double ensureFit(const std::string& volumePath, float eps, int degree, std::array<float, 2> range,
                     render::VotRenderer& vots, const Progress& progress = {});
    /// Uploads this rank's Vots of the .vots file (votsOfSlab: those whose box starts in its slab, or with
    /// `cutRays` every one that meets it) when they differ from what `vots` holds, reading the file when
    /// it is not the one kept; returns the milliseconds it took (0 when held).
    double ensureVotsFile(const std::string& votsPath, bool cutRays, render::VotRenderer& vots);
    /// The key ensureVotsFile compares.
    static std::string votsFileKey(const std::string& votsPath, bool cutRays);

    /// The frame's projection of this rank's Vots, rays cut to its cells where the composite needs it.
    SlabFrame draw(const render::FrameRequest& frame, render::VotRenderer& vots) const;

    /// Reads this rank's planes of the volume into `grid` when they are not the ones it holds; returns
    /// the milliseconds it took (0 when it held them).
    double ensureGrid(const std::string& volumePath, render::GridRenderer& grid);
    /// The frame's projection of this rank's planes on the exact grid (ensureGrid first).
    static SlabFrame drawGrid(const render::FrameRequest& frame, render::GridRenderer& grid);

    /// This rank's part of what the server knows of a volume (the samples' range, the content CRC), read
    /// from its slab's planes, which it keeps for the fits (heldSlab); see SlabSummary.
    SlabSummary summarize(const std::string& volumePath);

    /// The Vots of the slab fit held (0 before the first).
    std::size_t votCount() const { return mVotCount; }
    /// What that fit took, read and upload included (0 before the first).
    double fitMs() const { return mFitMs; }

    /// The key ensureFit compares.
    static std::string fitKey(const std::string& volumePath, float eps, int degree);

private:
    /// This rank's slab of the volume in the file's sample type, read (readOwnSlab) when it is not the
    /// one held; a new volume drops the box caches of the last.
    const std::pair<ZSlab, fit::VolumeSlab>& heldSlab(const std::string& volumePath);
    /// This rank's slab of the volume and its planes read with `storage`; throws server::RanksOverBudget,
    /// before reading, when they (and their fit) would need more than the memory budget leaves.
    std::pair<ZSlab, fit::VolumeSlab> readOwnSlab(const std::string& volumePath,
                                                  fit::SampleStorage storage) const;
    /// Uploads `space` (this rank's Vots of `slab`) and holds it under `key`; returns the milliseconds
    /// since `start`, which ensureFit and ensureVotsFile report.
    double hold(const fit::VotSpace& space, ZSlab slab, const std::string& key, bool fromFile,
                std::chrono::steady_clock::time_point start, render::VotRenderer& vots);
    int mRank;
    int mRanks;
    std::string mMemoryBudget;
    std::string mKey; // fitKey or votsFileKey of what the VotRenderer holds
    bool mFromFile = false;
    ZSlab mSlab;
    std::array<int, 3> mDims{0, 0, 0};
    std::size_t mVotCount = 0;
    double mFitMs = 0.0;
    std::string mGridPath;    // the volume whose planes ensureGrid last uploaded
    std::string mSamplesPath; // the volume heldSlab holds
    std::optional<std::pair<ZSlab, fit::VolumeSlab>> mSamples;
    std::map<int, std::unique_ptr<fit::FitCache>> mBoxCaches; // per degree, bound to mSamples' planes
    std::string mFilePath;                                    // the .vots file mFileVots was read from
    std::optional<fit::VotSpace> mFileVots; // its Vots that meet this rank's slab (ensureVotsFile)
};

} // namespace vots::cli
