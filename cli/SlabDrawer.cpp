// SlabDrawer: a rank's slab fitted as `mpirun vots render` fits it, and drawn for the composite.
#include "SlabDrawer.h"

#include "DistributedRender.h"
#include "MemoryBudgetOption.h"

#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/FrameCompositor.h"

#include <algorithm>
#include <chrono>
#include <cstring>

namespace vots::cli {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

ZSlab slabOfVolume(const std::string& volumePath, int rank, int ranks) {
    const auto planesZ = fit::volumeHeaderInfo(volumePath).dims[2];
    if (planesZ < 2) throw fit::InputError("volume needs at least 2 grid points along every axis");
    return zSlabOfRank(static_cast<int>(planesZ) - 1, rank, ranks);
}

} // namespace

std::pair<ZSlab, fit::VolumeSlab> SlabDrawer::readOwnSlab(const std::string& volumePath,
                                                          fit::SampleStorage storage) const {
    const ZSlab slab = slabOfVolume(volumePath, mRank, mRanks);
    const auto planes = static_cast<std::uint64_t>(std::max(slab.end - slab.first, 0)) + 1;
    const std::string refusal =
        planesBudgetRefusal(volumePath, std::nullopt, mMemoryBudget, "", planes, storage);
    if (!refusal.empty()) throw server::RanksOverBudget(refusal);
    return {slab, loadSlab(volumePath, slab, std::nullopt, storage, "")};
}

const std::pair<ZSlab, fit::VolumeSlab>& SlabDrawer::heldSlab(const std::string& volumePath) {
    if (mSamples && volumePath == mSamplesPath) return *mSamples;
    mBoxCaches.clear(); // bound to the planes about to go
    mSamples.reset();
    mSamplesPath.clear();
    // In the file's sample type: the same Vots as from floats (fit::SampleStorage), at half or a quarter of
    // the memory.
    mSamples = readOwnSlab(volumePath, fit::SampleStorage::Source);
    mSamplesPath = volumePath;
    return *mSamples;
}

std::string SlabDrawer::fitKey(const std::string& volumePath, float eps, int degree) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &eps, sizeof bits); // the exact eps: a key differs whenever the fit would
    return volumePath + '|' + std::to_string(bits) + '|' + std::to_string(degree);
}

double SlabDrawer::ensureFit(const std::string& volumePath, float eps, int degree, std::array<float, 2> range,
                             render::VotRenderer& vots, const Progress& progress) {
    const std::string key = fitKey(volumePath, eps, degree);
    if (key == mKey) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    mKey.clear(); // until the new fit is uploaded, nothing is held
    const auto& [slab, read] = heldSlab(volumePath);
    fit::FitOptions options;
    options.eps = eps;
    options.degree = degree;
    options.background = fit::defaultBackground(range);
    options.certify = render::RENDER_FIT_CERTIFY;
    options.progress = progress;
    fit::VotSpace space;
    if (!slab.empty()) {
        fit::validateFitOptions(read.planes, options);
        std::unique_ptr<fit::FitCache>& boxCache = mBoxCaches[degree];
        if (!boxCache) boxCache = std::make_unique<fit::FitCache>();
        space = fit::fitVotSpace(read.planes, options, boxCache.get()).space;
    }
    placeSlabFitInGrid(space, slab, read.whole);
    return hold(space, slab, key, false, start, vots);
}

double SlabDrawer::hold(const fit::VotSpace& space, ZSlab slab, const std::string& key, bool fromFile,
                        std::chrono::steady_clock::time_point start, render::VotRenderer& vots) {
    vots.upload(space);
    mVotCount = space.vots.size();
    mSlab = slab;
    mDims = space.dims;
    mKey = key;
    mFromFile = fromFile;
    mFitMs = msSince(start);
    return mFitMs;
}

std::string SlabDrawer::votsFileKey(const std::string& votsPath, bool cutRays) {
    return "file|" + votsPath + (cutRays ? "|cut" : "|whole");
}

double SlabDrawer::ensureVotsFile(const std::string& votsPath, bool cutRays, render::VotRenderer& vots) {
    const std::string key = votsFileKey(votsPath, cutRays);
    if (key == mKey) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    mKey.clear(); // until the new Vots are uploaded, nothing is held
    if (!mFileVots || votsPath != mFilePath) {
        mFileVots.reset();
        // The whole file is read and this rank's Vots kept, as `mpirun vots render FILE.vots` does: rank
        // 0's dataset registry has checked the file's size against the memory budget before any rank read it.
        fit::VotSpace space = fit::readVotSpaceFile(votsPath);
        if (space.dims[2] < 2) throw fit::InputError("a Vot-Space needs at least 2 grid points along z");
        const ZSlab slab = zSlabOfRank(space.dims[2] - 1, mRank, mRanks);
        mFileVots = votsOfSlab(std::move(space), slab, true);
        mFilePath = votsPath;
    }
    const ZSlab slab = zSlabOfRank(mFileVots->dims[2] - 1, mRank, mRanks);
    // The Vots whose box starts in the slab are among those that meet it: a change of mode reads nothing.
    if (cutRays) return hold(*mFileVots, slab, key, true, start, vots);
    return hold(votsOfSlab(*mFileVots, slab, false), slab, key, true, start, vots);
}

SlabSummary SlabDrawer::summarize(const std::string& volumePath) {
    // The planes the fits will take: the first fit reads nothing more.
    const auto& [slab, read] = heldSlab(volumePath);
    const int lastPlane = read.whole.dims[2] - 1;
    const int owned = slab.empty() ? 0 : slab.end - slab.first + (slab.end == lastPlane ? 1 : 0);
    const std::uint64_t planeBytes = static_cast<std::uint64_t>(read.whole.dims[0]) *
                                     static_cast<std::uint64_t>(read.whole.dims[1]) * sizeof(float);
    SlabSummary summary;
    summary.range = read.planes.valueRange();
    summary.gridCrc = read.whole.gridCrc();
    summary.crc = read.planes.planesCrc(0, owned);
    summary.bytes = planeBytes * static_cast<std::uint64_t>(owned);
    return summary;
}

SlabFrame SlabDrawer::draw(const render::FrameRequest& f, render::VotRenderer& vots) const {
    SlabFrame drawn;
    std::optional<render::CellDomain> domain;
    if (compositesCutRays(f.mode)) domain = cellDomainOfSlab(mSlab, mDims);
    vots.setRayDomain(domain);
    drawn.frame = vots.render(f.camera, f.width, f.height, render::RenderOptions{f.mode, f.slab});
    if (f.mode == render::RenderMode::Aip)
        drawn.lengths = vots.rayLengths(f.camera, f.width, f.height, f.slab);
    if (f.mode == render::RenderMode::Density)
        drawn.displayRange = vots.densityRange();
    else if (mFromFile)
        drawn.displayRange = vots.valueRange();
    vots.setRayDomain(std::nullopt);
    return drawn;
}

double SlabDrawer::ensureGrid(const std::string& volumePath, render::GridRenderer& grid) {
    if (volumePath == mGridPath) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    mGridPath.clear(); // until the new planes are uploaded, nothing is held
    // An empty slab (more ranks than cells) still reads its one plane and draws nothing of its own.
    const auto [slab, read] = readOwnSlab(volumePath, fit::SampleStorage::Float);
    grid.uploadSlab(read.planes, slab.first, read.whole);
    mGridPath = volumePath;
    return msSince(start);
}

SlabFrame SlabDrawer::drawGrid(const render::FrameRequest& f, render::GridRenderer& grid) {
    SlabFrame drawn;
    drawn.frame = grid.render(f.camera, f.width, f.height, render::RenderOptions{f.mode, f.slab});
    drawn.fromGrid = true;
    return drawn;
}

} // namespace vots::cli
