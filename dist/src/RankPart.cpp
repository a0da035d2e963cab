// RankPart: a rank's cells fitted as `mpirun vots render` fits them, and drawn for the composite.
#include "vots/dist/RankPart.h"

#include "vots/dist/CompositeOp.h"
#include "vots/dist/Failure.h"

#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/VotRenderer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace vots::dist {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string exactText(float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits); // exact: an identity differs whenever the value does
    return std::to_string(bits);
}

/// One frame of one volume file, as the identities of held planes and fits name it.
std::string volumeFrameId(const std::string& volumePath, int frame) {
    return volumePath + '|' + std::to_string(frame);
}

} // namespace

RankPart::RankPart(int rank, int ranks, RankSetup setup)
    : mRank(rank), mRanks(ranks), mSetup(std::move(setup)) {}

RankPart::HeldPlanes RankPart::readOwnPlanes(const std::string& volumePath, int frame,
                                             fit::SampleStorage storage) const {
    const RankCells cells = cellsOfRankInVolume(volumePath, mRank, mRanks);
    const auto planes = static_cast<std::uint64_t>(std::max(cells.end - cells.first, 0)) + 1;
    if (mSetup.planesOverBudget) {
        const std::string refusal = mSetup.planesOverBudget(volumePath, planes, storage);
        if (!refusal.empty()) throw RanksOverBudget(refusal);
    }
    return {cells, loadPlanesOfCells(volumePath, cells, std::nullopt, storage, "", frame)};
}

const RankPart::HeldPlanes& RankPart::heldPlanes(const std::string& volumePath, int frame) {
    const std::string id = volumeFrameId(volumePath, frame);
    if (mPlanes && id == mPlanesPath) return *mPlanes;
    mBoxCaches.clear(); // bound to the planes about to go
    mPlanes.reset();
    mPlanesPath.clear();
    // In the file's sample type: the same Vots as from floats (fit::SampleStorage), at half or a quarter of
    // the memory.
    mPlanes = readOwnPlanes(volumePath, frame, fit::SampleStorage::Source);
    mPlanesPath = id;
    return *mPlanes;
}

std::string RankPart::cellsFitId(const std::string& volumePath, int frame, float eps, int degree,
                                 fit::FitNorm norm) {
    return volumeFrameId(volumePath, frame) + '|' + exactText(eps) + '|' + std::to_string(degree) + '|' +
           std::string(fit::nameOf(norm));
}

std::string RankPart::votsFileId(const std::string& votsPath, bool cutRays) {
    return "file|" + votsPath + (cutRays ? "|cut" : "|whole");
}

RankFit RankPart::fit(const std::string& volumePath, int frame, float eps, int degree, fit::FitNorm norm,
                      std::array<float, 2> range, const FitProgress& progress) {
    const std::string id = cellsFitId(volumePath, frame, eps, degree, norm);
    if (id == mFitId) {
        RankFit held = mFitDone;
        held.fitMs = 0.0;
        return held;
    }
    const auto start = std::chrono::steady_clock::now();
    mFitId.clear(); // until the new fit is made, nothing is held
    mFitted.reset();
    const auto& [cells, read] = heldPlanes(volumePath, frame);
    fit::FitOptions options = render::renderFitOptions(eps, degree, fit::defaultBackground(range),
                                                       render::RENDER_FIT_CERTIFY, norm);
    options.noDataValue = range[0]; // the whole volume's lowest finite sample, as on every other rank
    options.progress = progress;
    fit::FitResult fitted;
    if (!cells.empty()) {
        fit::validateFitOptions(read.planes, options);
        // (A cache is bound to one norm: another one clears it.)
        std::unique_ptr<fit::FitCache>& boxCache = mBoxCaches[degree];
        if (!boxCache) boxCache = std::make_unique<fit::FitCache>();
        fitted = fit::fitVotSpace(read.planes, options, boxCache.get());
    }
    placeCellsFitInGrid(fitted.space, cells, read.whole);
    mFitDone.background = backgroundSumsOf(fitted.stats);
    mFitDone.votCount = fitted.space.vots.size();
    mFitDone.fitMs = mFitDone.heldFitMs = msSince(start);
    mFitted = std::move(fitted.space);
    mFittedCells = cells;
    mFitId = id;
    return mFitDone;
}

double RankPart::uploadFit(const std::string& volumePath, int frame, float eps, int degree, fit::FitNorm norm,
                           std::optional<float> wholeFill, render::VotRenderer& vots) {
    const std::string id = cellsFitId(volumePath, frame, eps, degree, norm);
    if (id != mFitId)
        throw std::runtime_error("rank " + std::to_string(mRank) + " holds no fit of this frame");
    const std::string uploadId = id + "|fill " + (wholeFill ? exactText(*wholeFill) : "none");
    if (uploadId == mUploadedId) return 0.0;
    if (!mFitted) throw std::logic_error("RankPart: the fit held was uploaded with another fill");
    const auto start = std::chrono::steady_clock::now();
    mFitted->backgroundFill = wholeFill;
    upload(*mFitted, mFittedCells, uploadId, false, vots);
    mFitted.reset(); // on the GPU now; the same fit always has the same fill
    mFitMs = mFitDone.heldFitMs + msSince(start);
    return msSince(start);
}

void RankPart::upload(const fit::VotSpace& space, RankCells cells, const std::string& id, bool fromFile,
                      render::VotRenderer& vots) {
    mUploadedId.clear(); // until the upload is done, nothing is held
    vots.upload(space);
    mVotCount = space.vots.size();
    mCells = cells;
    mDims = space.dims;
    mUploadedId = id;
    mFromFile = fromFile;
}

double RankPart::ensureVotsFile(const std::string& votsPath, bool cutRays, render::VotRenderer& vots) {
    const std::string id = votsFileId(votsPath, cutRays);
    if (id == mUploadedId) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    if (!mFileVots || votsPath != mFilePath) {
        mFileVots.reset();
        // The whole file is read and this rank's Vots kept, as `mpirun vots render FILE.vots` does: rank
        // 0's dataset registry has checked the file's size against the memory budget before any rank read it.
        fit::VotSpace space = meta::readVotSpaceFile(votsPath);
        if (space.dims[2] < 2) throw fit::InputError("a Vot-Space needs at least 2 grid points along z");
        const RankCells cells = cellsOfRank(space.dims[2] - 1, mRank, mRanks);
        mFileVots = votsOfCells(std::move(space), cells, true);
        mFilePath = votsPath;
    }
    const RankCells cells = cellsOfRank(mFileVots->dims[2] - 1, mRank, mRanks);
    // The Vots whose box starts in the cells are among those that meet them: a change of mode reads nothing.
    if (cutRays)
        upload(*mFileVots, cells, id, true, vots);
    else
        upload(votsOfCells(*mFileVots, cells, false), cells, id, true, vots);
    mFitMs = msSince(start);
    return mFitMs;
}

RankSummary RankPart::summarize(const std::string& volumePath, int frame) {
    // The planes the fits will take: the first fit reads nothing more.
    const auto& [cells, read] = heldPlanes(volumePath, frame);
    const int lastPlane = read.whole.dims[2] - 1;
    const int owned = cells.empty() ? 0 : cells.end - cells.first + (cells.end == lastPlane ? 1 : 0);
    const std::uint64_t planeBytes = static_cast<std::uint64_t>(read.whole.dims[0]) *
                                     static_cast<std::uint64_t>(read.whole.dims[1]) * sizeof(float);
    RankSummary summary;
    summary.range = read.planes.valueRange();
    summary.gridCrc = read.whole.gridCrc();
    summary.crc = read.planes.planesCrc(0, owned);
    summary.bytes = planeBytes * static_cast<std::uint64_t>(owned);
    return summary;
}

RankFrame RankPart::draw(const render::FrameRequest& f, render::VotRenderer& vots) const {
    if (mUploadedId.empty()) throw std::logic_error("RankPart::draw: no Vots uploaded");
    RankFrame drawn;
    std::optional<render::CellDomain> domain;
    if (compositesCutRays(f.mode)) domain = cutRayDomainOf(mCells, mDims);
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

double RankPart::ensureGrid(const std::string& volumePath, int frame, render::GridRenderer& grid) {
    const std::string id = volumeFrameId(volumePath, frame);
    if (id == mGridPath) return 0.0;
    const auto start = std::chrono::steady_clock::now();
    mGridPath.clear(); // until the new planes are uploaded, nothing is held
    // An empty range of cells (more ranks than cells) still reads its one plane and draws nothing of its own.
    const auto [cells, read] = readOwnPlanes(volumePath, frame, fit::SampleStorage::Float);
    grid.uploadPlanes(read.planes, cells.first, read.whole);
    mGridPath = id;
    return msSince(start);
}

RankFrame RankPart::drawGrid(const render::FrameRequest& f, render::GridRenderer& grid) {
    RankFrame drawn;
    drawn.frame = grid.render(f.camera, f.width, f.height, render::RenderOptions{f.mode, f.slab});
    drawn.source = RankSource::Grid;
    return drawn;
}

} // namespace vots::dist
