// One rank's part of a distributed frame or fit: its z cells read once, fitted with the whole volume's
// options, uploaded with the whole volume's background fill, and drawn as a float frame.
#pragma once

#include "vots/dist/FrameComposite.h"
#include "vots/dist/RankCells.h"
#include "vots/dist/WholeFill.h"

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

namespace vots::dist {

/// A fit's progress is the fitter's own callback type.
using fit::FitProgress;

/// What a rank's part needs from the layers above it, given by the command line's wiring.
struct RankSetup {
    /// Why reading `planes` z planes of the volume with `storage` (and fitting them) would exceed the
    /// memory budget, or empty when they fit; asked before every read of the rank's planes, whose refusal
    /// is thrown as RanksOverBudget. Unset: no budget.
    std::function<std::string(const std::string& path, std::uint64_t planes, fit::SampleStorage storage)>
        planesOverBudget;
};

/// One rank's reading of its cells of a volume. Each plane is owned by one rank (its cells' first planes,
/// and the last plane by the rank whose cells end there), so chaining the ranks' `crc` in rank order from
/// `gridCrc` with fit::combineCrc gives the volume's fit::Volume::contentCrc.
struct RankSummary {
    std::array<float, 2> range{0.f, 0.f}; // min and max sample of the rank's planes
    std::uint32_t gridCrc = 0;            // of the whole volume's grid, the same on every rank
    std::uint32_t crc = 0;                // of the planes this rank owns, as floats
    std::uint64_t bytes = 0;              // their bytes as floats
};

/// What a rank's fit of its cells gave.
struct RankFit {
    BackgroundSums background; // its part of the whole volume's fill (wholeVolumeFill)
    std::uint64_t votCount = 0;
    double fitMs = 0.0;     // this call's (0 when the fit was held)
    double heldFitMs = 0.0; // what the held fit took, whenever it was made
};

/// The fit of a volume's cells as `mpirun vots render VOLUME --eps` makes it (automatic background, cells
/// certified), kept while the volume, eps, degree and norm stay the same; or the rank's Vots of a .vots file.
/// The rank's samples are read once and kept, with a box cache per degree, as one process keeps a
/// study's: a refit at a new eps reuses the boxes fitted before. Not thread-safe.
class RankPart {
public:
    RankPart(int rank, int ranks, RankSetup setup);

    /// Reads (once) and fits this rank's planes of `frame` (the 3D volume of a 4D file; 0 otherwise)
    /// unless the fit of (volume, frame, eps, degree, norm) is held; `range` is the whole volume's. The fit
    /// reports through `progress` when it is set. Needs no renderer.
    RankFit fit(const std::string& volumePath, int frame, float eps, int degree, fit::FitNorm norm,
                std::array<float, 2> range, const FitProgress& progress = {});
    /// Uploads the held fit of (volume, frame, eps, degree, norm) to `vots` with the whole volume's
    /// background fill (wholeVolumeFill of every rank's RankFit) unless `vots` holds it already; returns the
    /// milliseconds it took. Throws std::runtime_error when that fit is not the one held.
    double uploadFit(const std::string& volumePath, int frame, float eps, int degree, fit::FitNorm norm,
                     std::optional<float> wholeFill, render::VotRenderer& vots);
    /// Uploads this rank's Vots of the .vots file (votsOfCells: those whose box starts in its cells, or
    /// with `cutRays` every one that meets them) when they differ from what `vots` holds, reading the file
    /// when it is not the one kept; returns the milliseconds it took (0 when held).
    double ensureVotsFile(const std::string& votsPath, bool cutRays, render::VotRenderer& vots);

    /// The frame's projection of this rank's Vots, rays cut to its cells where the composite needs it.
    RankFrame draw(const render::FrameRequest& frame, render::VotRenderer& vots) const;

    /// Reads this rank's planes of the volume's `frame` into `grid` when they are not the ones it holds;
    /// returns the milliseconds it took (0 when it held them).
    double ensureGrid(const std::string& volumePath, int frame, render::GridRenderer& grid);
    /// The frame's projection of this rank's planes on the exact grid (ensureGrid first).
    static RankFrame drawGrid(const render::FrameRequest& frame, render::GridRenderer& grid);

    /// This rank's part of what the server knows of a volume (the samples' range, the content CRC), read
    /// from its planes of `frame`, which it keeps for the fits; see RankSummary.
    RankSummary summarize(const std::string& volumePath, int frame);

    /// The Vots uploaded last (0 before the first).
    std::size_t votCount() const { return mVotCount; }
    /// What the fit (or read) of the Vots uploaded last took, upload included (0 before the first).
    double fitMs() const { return mFitMs; }

    /// The identity of a rank's fit of its cells: the volume and frame, the exact eps, the degree, the norm.
    static std::string cellsFitId(const std::string& volumePath, int frame, float eps, int degree,
                                  fit::FitNorm norm);
    /// The identity of the Vots of a .vots file a rank uploads for whole or cut rays.
    static std::string votsFileId(const std::string& votsPath, bool cutRays);

private:
    using HeldPlanes = std::pair<RankCells, fit::PlanesOfGrid>;
    /// This rank's planes of the volume's frame in the file's sample type, read (readOwnPlanes) when they
    /// are not the ones held; a new volume or frame drops the box caches of the last.
    const HeldPlanes& heldPlanes(const std::string& volumePath, int frame);
    /// This rank's cells of the volume and its planes of `frame` read with `storage`; throws
    /// RanksOverBudget, before reading, when they (and their fit) would need more than the memory budget
    /// leaves.
    HeldPlanes readOwnPlanes(const std::string& volumePath, int frame, fit::SampleStorage storage) const;
    /// Uploads `space` (this rank's Vots of `cells`) and marks it as `vots`'s, under `id`.
    void upload(const fit::VotSpace& space, RankCells cells, const std::string& id, bool fromFile,
                render::VotRenderer& vots);
    int mRank;
    int mRanks;
    RankSetup mSetup;
    // What the VotRenderer holds.
    std::string mUploadedId; // cellsFitId plus the fill, or votsFileId
    bool mFromFile = false;
    RankCells mCells;
    std::array<int, 3> mDims{0, 0, 0};
    std::size_t mVotCount = 0;
    double mFitMs = 0.0;
    // The fit held: its identity, its result until uploaded, and what it gave.
    std::string mFitId;
    std::optional<fit::VotSpace> mFitted;
    RankCells mFittedCells;
    RankFit mFitDone;
    std::string mGridPath;   // volumeFrameId of the planes ensureGrid last uploaded
    std::string mPlanesPath; // volumeFrameId of the planes heldPlanes holds
    std::optional<HeldPlanes> mPlanes;
    std::map<int, std::unique_ptr<fit::FitCache>> mBoxCaches; // per degree, bound to mPlanes
    std::string mFilePath;                                    // the .vots file mFileVots was read from
    std::optional<fit::VotSpace> mFileVots; // its Vots that meet this rank's cells (ensureVotsFile)
};

} // namespace vots::dist
