// fitVotSpace: validates options, builds the background mask, runs a generator, assembles the Vot-Space.
#include "vots/fit/Fitter.h"

#include "BoxFit.h"
#include "BoxTester.h"
#include "CellMask.h"
#include "FitCacheImpl.h"
#include "PaperGrowth.h"
#include "ParallelFor.h"
#include "SplitMerge.h"
#include "vots/fit/Error.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace vots::fit {

float defaultBackground(const Volume& volume) {
    return defaultBackground(volume.valueRange());
}

float defaultBackground(std::array<float, 2> range) {
    return range[0] + 0.01f * (range[1] - range[0]);
}

std::optional<float> backgroundFillOf(const FitStats& stats) {
    if (stats.backgroundCells == 0) return std::nullopt;
    return static_cast<float>(stats.backgroundValueSum / static_cast<double>(stats.backgroundCells));
}

void validateFitOptions(const Volume& volume, const FitOptions& options) {
    if (!std::isfinite(options.eps) || options.eps <= 0.f)
        throw InputError("eps must be a finite number > 0 (got " + std::to_string(options.eps) + ")");
    if (options.degree < 0 || options.degree > 3)
        throw InputError("degree must be 0, 1, 2 or 3 (got " + std::to_string(options.degree) + ")");
    if (options.background && std::isnan(*options.background))
        throw InputError("background threshold is NaN");
    if (options.threads < 0 || options.threads > 256) throw InputError("threads must be between 0 and 256");
    for (int a = 0; a < 3; ++a)
        if (volume.dims[a] < 2)
            throw InputError("volume needs at least 2 grid points along every axis to form a cell");
    if (volume.heldSamples() != volume.sampleCount())
        throw InputError("volume sample count does not match its dims");
    // A rank's planes may all be no data (the volume's other planes hold its data); a whole volume not.
    if (!options.partOfGrid && volume.nonFiniteCount() == volume.sampleCount())
        throw InputError("all " + std::to_string(volume.sampleCount()) +
                         " samples are NaN or Inf: the volume holds no data");
    std::array<int, 3> gridDims = volume.dims;
    if (options.partOfGrid) {
        gridDims = options.partOfGrid->gridDims;
        const int first = options.partOfGrid->firstPlane;
        if (gridDims[0] != volume.dims[0] || gridDims[1] != volume.dims[1] || first < 0 ||
            static_cast<long long>(first) + volume.dims[2] > gridDims[2])
            throw InputError("the volume is not a run of z planes of the grid it is placed in");
    }
    if (options.focus) {
        const auto& f = *options.focus;
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(f.centerIndex[a]) || f.centerIndex[a] < 0.0 ||
                f.centerIndex[a] > gridDims[a] - 1)
                throw InputError("focus centre must lie inside the grid (index space)");
        if (!std::isfinite(f.radius) || f.radius <= 0.0) throw InputError("focus radius must be > 0");
        if (!std::isfinite(f.epsFocus) || f.epsFocus < 0.f || f.epsFocus > options.eps)
            throw InputError("eps-focus must be between 0 and eps");
    }
}

FitResult fitVotSpace(const Volume& volume, const FitOptions& options, FitCache* cache) {
    validateFitOptions(volume, options);
    const auto start = std::chrono::steady_clock::now();

    std::optional<FocusRegion> focus = options.focus; // in the fitted volume's own index space
    if (focus && options.partOfGrid) focus->centerIndex[2] -= options.partOfGrid->firstPlane;
    const EpsField eps(options.eps, focus);
    const BoxFitter fitter(volume, options.degree, options.certify, options.norm);
    FitCounters counters;
    FitCache::Impl* cacheImpl = nullptr;
    if (cache) {
        cacheImpl = &cache->impl();
        cacheImpl->bind(volume, options.degree, options.certify, options.norm);
    }
    const std::shared_ptr<const CellMask> maskOwner =
        cacheImpl ? cacheImpl->maskFor(volume, options.background, options.noDataValue)
                  : std::make_shared<const CellMask>(volume, options.background, options.noDataValue);
    const CellMask& mask = *maskOwner;
    const BoxTester tester(fitter, eps, counters, cacheImpl);
    const FitControl control{resolveThreadCount(options.threads), options.progress, options.cancel};

    std::vector<FittedBox> boxes;
    if (options.method == FitMethod::Paper) {
        boxes = greedyCover(growSeeds(mask, tester, control), mask, control);
    } else {
        boxes = splitZones(mask, tester, control);
        if (control.progress) control.progress(0.9, "merge");
        mergeAcrossZones(boxes, tester, control);
    }
    if (control.progress) control.progress(1.0, "done");

    FitResult result;
    VotSpace& space = result.space;
    space.dims = volume.dims;
    space.origin = volume.origin;
    space.spacing = volume.spacing;
    space.patientAxes = volume.patientAxes;
    space.orientationKnown = volume.orientationKnown;
    space.eps = options.eps;
    space.background = options.background ? *options.background : std::numeric_limits<float>::lowest();
    space.epsVaries = eps.varies();
    space.degree = 0;
    space.vots.reserve(boxes.size());
    for (const auto& fb : boxes) {
        Vot vot;
        vot.box = fb.box;
        vot.p = fb.outcome.p;
        vot.err = fb.outcome.errSamples;
        vot.c = fb.outcome.c;
        space.degree = std::max(space.degree, vot.effectiveDegree());
        result.stats.maxError = std::max(result.stats.maxError, static_cast<double>(vot.err));
        space.vots.push_back(vot);
    }
    result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    result.stats.boxFits = counters.fits();
    result.stats.boxScans = counters.scans();
    result.stats.cacheHits = counters.cacheHits();
    result.stats.minimaxFits = counters.minimaxFits();
    result.stats.minimaxScans = counters.minimaxScans();
    result.stats.minimaxAccepted = counters.minimaxAccepted();
    result.stats.centredAccepted = counters.centredAccepted();
    result.stats.coveredCells = static_cast<std::size_t>(mask.totalForeground());
    result.stats.backgroundCells = static_cast<std::size_t>(mask.totalBackground());
    result.stats.backgroundValueSum = mask.backgroundValueSum();
    space.backgroundFill = backgroundFillOf(result.stats);
    return result;
}

} // namespace vots::fit
