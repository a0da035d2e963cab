// Vot MIP and density: the upload (bounds, records, order) and the dispatch to the walk or raster pass.
#include "vots/render/VotRenderer.h"

#include "CpuSplat.h"
#include "FloatTarget.h"
#include "FrameReadout.h"
#include "ParallelChunks.h"
#include "RasterPass.h"
#include "VotBounds.h"
#include "VotOrder.h"
#include "WalkPass.h"
#include "WalkRecord.h"

#include "vots/fit/Error.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/EglContext.h"
#include "vots/render/GpuLayout.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string_view>

namespace vots::render {

struct VotRenderer::Impl {
    WalkPass walk;
    RasterPass raster;
    CpuSplat splat;
    bool splatStale = true; // the splat's copy of the Vots predates the last upload
    // The walk's grid and tables are built at the first frame that walks, not at the upload, where the
    // splat draws the MIP: an eps move's first image waits for the upload, and a MinIP may never come.
    // Until then the upload keeps what the build needs.
    struct PendingWalk {
        std::unique_ptr<std::uint32_t[]> records; // WALK_RECORD_WORDS per Vot, in d.vots' order
        std::array<int, 3> dims{0, 0, 0};
        float omittedCellValue = 0.f;
    };
    std::optional<PendingWalk> pendingWalk;
    FloatTarget target;

    bool hasData = false;
    SceneBounds bounds;
    std::vector<GpuVot> vots; // in space order when walkable, else by descending upperBound
    std::array<float, 2> valueRange{0.f, 0.f};
    std::array<float, 2> densityRange{0.f, 1.f};
    bool culling = true;
    Strategy strategy = defaultStrategy();
    std::optional<CellDomain> domain;
    std::array<int, 3> cells{0, 0, 0};
    FrameStats stats;

    static Strategy defaultStrategy() {
        const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        return renderer && EglContext::isSoftwareRenderer(renderer) ? Strategy::Splat : Strategy::Walk;
    }

    Strategy mipStrategy() {
        if (strategy == Strategy::Splat) return Strategy::Splat;
        buildWalk();
        return strategy == Strategy::Walk && walk.walkable() ? Strategy::Walk : Strategy::Raster;
    }

    void buildWalk() {
        if (!pendingWalk) return;
        PendingWalk pending = std::move(*pendingWalk);
        pendingWalk.reset();
        std::optional<WalkPass::Grid> grid = WalkPass::gridFor(vots, pending.dims);
        if (!grid) {
            // Bound order when Raster draws the MIP instead; the walk is never drawn, its records unused.
            const std::vector<std::size_t> byBound = boundOrder(vots);
            std::vector<GpuVot> inSpaceOrder = std::move(vots);
            vots.resize(byBound.size());
            for (std::size_t i = 0; i < byBound.size(); ++i)
                vots[i] = inSpaceOrder[byBound[i]];
        }
        walk.upload(std::move(grid), vots, pending.records.get(), pending.omittedCellValue);
    }

    /// A MIP the splat draws on the CPU; nullopt for every other frame (drawn into `target`).
    std::optional<FloatImage> draw(const Camera& camera, int width, int height,
                                   const RenderOptions& options) {
        const RenderMode mode = options.mode;
        if (mode == RenderMode::Density && options.slab)
            throw fit::InputError("density shows the smallest Vot along each whole ray; it takes no slab");
        if (!hasData) throw fit::GraphicsError("VotRenderer: render() before upload()");
        const CameraMatrices m = computeCameraMatrices(camera, bounds, width, height);
        const auto t0 = FrameClock::now();
        stats = FrameStats{};
        stats.votsTotal = vots.size();
        const bool alongRays = mode == RenderMode::MinIp || mode == RenderMode::Aip;
        if (alongRays) buildWalk();
        // The walk's per-cell view is what gives the min and the mean their background cells and the
        // mean its non-overlapping segments; the raster strategy sees only boxes.
        if (alongRays && !walk.walkable())
            throw fit::InputError(
                std::string(renderModeName(mode)) +
                " needs a Vot-Space with disjoint boxes (fit --method fast) within the walk's "
                "GL limits; this one can only be drawn as mip or density");
        const Strategy mipBy = mipStrategy();
        const bool splatted = mode == RenderMode::Mip && mipBy == Strategy::Splat;
        const bool walked = alongRays || (mode == RenderMode::Mip && mipBy == Strategy::Walk);
        if (domain && !walked && !splatted)
            throw fit::InputError(std::string(renderModeName(mode)) +
                                  " is drawn from boxes here, not cells: it takes no cell domain");
        std::optional<SlabPlanes> slab;
        if (options.slab) slab = slabPlanesInIndexSpace(*options.slab, camera, bounds);
        if (splatted) {
            if (splatStale) splat.upload(vots);
            splatStale = false;
            FloatImage image =
                splat.draw(m, slab, domain, cells, width, height, culling, options.abandoned, stats);
            stats.gpuMs = msSince(t0);
            return image;
        }
        target.bind(width, height);
        if (walked)
            walk.draw(mode, m, slab, domain, width, height, target, culling, stats, options.abandoned);
        else
            raster.draw(mode, m, slab, width, height, target, vots, culling, stats);
        glDisable(GL_CULL_FACE);
        glFinish();
        stats.gpuMs = msSince(t0);
        checkGl(walked ? "VotRenderer walk" : "VotRenderer draw");
        if (walked) walk.startSkipGrowth();
        return std::nullopt;
    }
};

void VotRenderer::setRayDomain(std::optional<CellDomain> domain) {
    mImpl->domain = domain;
}
const std::optional<CellDomain>& VotRenderer::rayDomain() const {
    return mImpl->domain;
}

FloatImage VotRenderer::rayLengths(const Camera& camera, int width, int height,
                                   const std::optional<Slab>& slab) {
    Impl& d = *mImpl;
    if (!d.hasData) throw fit::GraphicsError("VotRenderer: rayLengths() before upload()");
    d.buildWalk();
    if (!d.walk.walkable())
        throw fit::InputError(
            "ray lengths are the walk's: this Vot-Space can only be drawn as mip or density");
    const CameraMatrices m = computeCameraMatrices(camera, d.bounds, width, height);
    std::optional<SlabPlanes> planes;
    if (slab) planes = slabPlanesInIndexSpace(*slab, camera, d.bounds);
    d.target.bind(width, height);
    d.walk.drawRayLengths(m, planes, d.domain, width, height, d.target);
    glDisable(GL_CULL_FACE);
    glFinish();
    checkGl("VotRenderer ray lengths");
    FrameStats unused;
    return readFloatFrame(d.target, unused);
}

VotRenderer::VotRenderer() : mImpl(std::make_unique<Impl>()) {}
VotRenderer::~VotRenderer() = default;

void VotRenderer::upload(const fit::VotSpace& space) {
    Impl& d = *mImpl;
    d.walk.cancelSkipGrowth();
    std::vector<VotBounds> bounds(space.vots.size());
    // Records go straight to their place in space order (the walk's order), not through a copy: a refit
    // waits for the upload.
    const std::vector<std::size_t> order = spatialOrder(space.vots);
    std::vector<std::size_t> place(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        place[order[i]] = i;
    d.vots.resize(space.vots.size());
    Impl::PendingWalk pending;
    // Left uninitialised: every word is written below.
    pending.records.reset(new std::uint32_t[space.vots.size() * WALK_RECORD_WORDS]);
    // Bounds and records dominate an upload; each Vot is independent, so split evenly.
    parallelChunks(space.vots.size(), [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            bounds[i] = computeVotBounds(space.vots[i]);
            const WalkRecord walk = makeWalkRecord(space.vots[i]);
            std::copy(walk.words.begin(), walk.words.end(), &pending.records[place[i] * WALK_RECORD_WORDS]);
            // The walk evaluates its record's polynomial, which strays from the Vot's by up to
            // maxError: every bound covers both, so culling by it never changes either image.
            bounds[i].floatSlack += walk.maxError;
            d.vots[place[i]] = makeGpuVot(space.vots[i], bounds[i]);
        }
    });
    d.raster.upload(d.vots.size());
    pending.dims = space.dims;
    pending.omittedCellValue = space.omittedCellValue();
    d.pendingWalk = std::move(pending);

    float lo = INFINITY, hi = -INFINITY, maxLogSize = 0.f;
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        lo = std::min(lo, static_cast<float>(bounds[i].lower));
        hi = std::max(hi, static_cast<float>(bounds[i].upper));
        maxLogSize = std::max(maxLogSize, d.vots[i].logSize);
    }
    if (d.vots.empty()) lo = hi = 0.f;
    d.valueRange = {lo, hi};
    d.densityRange = {0.f, std::max(maxLogSize, 1.f)};

    d.bounds = sceneBounds(space);
    for (std::size_t a = 0; a < 3; ++a)
        d.cells[a] = space.dims[a] - 1;
    d.splatStale = true;
    d.hasData = true;
    if (d.strategy != Strategy::Splat) d.buildWalk();
}

bool VotRenderer::hasData() const {
    return mImpl->hasData;
}
const SceneBounds& VotRenderer::bounds() const {
    return mImpl->bounds;
}
std::array<float, 2> VotRenderer::valueRange() const {
    return mImpl->valueRange;
}
std::array<float, 2> VotRenderer::densityRange() const {
    return mImpl->densityRange;
}
void VotRenderer::setCulling(bool enabled) {
    mImpl->culling = enabled;
}
void VotRenderer::setStrategy(Strategy strategy) {
    mImpl->strategy = strategy;
}
VotRenderer::Strategy VotRenderer::strategy() const {
    return mImpl->strategy;
}
VotRenderer::Strategy VotRenderer::mipStrategy() const {
    return mImpl->mipStrategy();
}
std::string_view strategyName(VotRenderer::Strategy strategy) {
    switch (strategy) {
    case VotRenderer::Strategy::Walk:
        return "walk";
    case VotRenderer::Strategy::Raster:
        return "raster";
    case VotRenderer::Strategy::Splat:
        return "splat";
    }
    return "walk";
}

std::string_view walkShaderName(VotRenderer::WalkShader shader) {
    return shader == VotRenderer::WalkShader::Compute ? "compute" : "fragment";
}

std::optional<VotRenderer::WalkShader> parseWalkShader(std::string_view name) {
    for (const auto shader : {VotRenderer::WalkShader::Fragment, VotRenderer::WalkShader::Compute})
        if (name == walkShaderName(shader)) return shader;
    return std::nullopt;
}

void VotRenderer::setWalkShader(WalkShader shader) {
    mImpl->walk.useShader(shader);
}
VotRenderer::WalkShader VotRenderer::walkShader() const {
    return mImpl->walk.shader();
}
void VotRenderer::setBackgroundThreadStart(std::function<void()> onStart) {
    mImpl->walk.setBackgroundThreadStart(std::move(onStart));
}

void VotRenderer::finishPendingWork() {
    if (mImpl->pendingWalk) return; // nothing walked yet: no skip boxes to grow
    mImpl->walk.startSkipGrowth();
    mImpl->walk.applySkipBoxes(true);
}
const FrameStats& VotRenderer::lastFrameStats() const {
    return mImpl->stats;
}

FloatImage VotRenderer::render(const Camera& camera, int width, int height, const RenderOptions& options) {
    if (std::optional<FloatImage> drawn = mImpl->draw(camera, width, height, options))
        return std::move(*drawn);
    return readFloatFrame(mImpl->target, mImpl->stats);
}

} // namespace vots::render
