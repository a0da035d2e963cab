// Vot MIP and Vot density images of a Vot-Space: per-pixel walk through a cell -> Vot grid, or one
// instanced unit cube per Vot into R32F with GL_MAX/GL_MIN.
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/CellDomain.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/FrameStats.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"
#include "vots/render/Renderer.h"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

namespace vots::fit {
struct VotSpace;
}

namespace vots::render {

/// Keeps the Vots in GPU buffers, so frames after upload() are cheap. Needs a current EglContext
/// for its whole life (construct, use and destroy it on the context's thread).
///
/// The MIP strategies give the same image (up to rays grazing a face within 5e-5 voxel, and the walk's
/// 16-bit higher-order terms: WalkRecord.h, at most 2.5e-4 of a Vot's largest such term); all use a
/// certified upper bound of each Vot over its box (Bernstein form, widened to cover both), computed at
/// upload.
///
/// Walk (default on a GPU): one compute invocation per pixel (on llvmpipe: one pass over the back faces of
/// the grid box, see WalkShader); each pixel walks its ray front to back through a grid holding, per cell,
/// the Vot covering it (background cells: near-cubic empty blocks), and per brick of 16^3 cells the largest
/// bound of the Vots touching it. Bricks and Vot boxes whose bound cannot beat the pixel's current max, and
/// empty blocks, are stepped over whole (a culled Vot together with the neighbours its bound also culls, once
/// their skip boxes are grown after the first frame); a ray stops once no brick its view can still reach may
/// beat its max; the other Vots are evaluated with the same analytic maximum as Raster, from a 64-byte copy
/// of their record (one cache line instead of two: the walk waits on memory). Needs disjoint boxes (the fast
/// fit method); a Vot-Space with overlapping boxes (paper method) or beyond the GL limits is drawn with
/// Raster instead, see mipStrategy(). Density images always use Raster. The walk is render/src/WalkPass.*,
/// the raster strategy render/src/RasterPass.*; docs/DESIGN.md §6 and §7.
///
/// Raster: one instanced unit cube per Vot. With culling, Vots are drawn in batches, in descending
/// order of their bound when Raster is the MIP strategy (records are in space order for the walk); between
/// batches the current max image is read back; a Vot whose bound cannot exceed the smallest max over the
/// pixels its box covers is not drawn, and fragments whose Vot bound is below the pixel's max stop early.
///
/// Splat: the MIP on the CPU's cores without GL (render/src/CpuSplat.h), where the GL context is a CPU
/// rasteriser: 2.4-3x faster than llvmpipe's walk for a still (bench/RESULTS.md). It evaluates the Vots'
/// own polynomials, as Raster does, and takes any Vot-Space. MinIP, average and density keep the walk
/// or Raster on any machine.
///
/// Culling never changes the image (dropped work could only produce values <= the pixel's max); a
/// test checks it for both strategies.
class VotRenderer final : public Renderer {
public:
    enum class Strategy {
        Walk,   // per-pixel ray walk through the cell -> Vot grid (default on a GPU)
        Raster, // instanced boxes, MAX blending
        Splat   // MIP on the CPU's cores, Vots in order of falling bound over their footprints (default
                // on a CPU rasteriser such as llvmpipe; render/src/CpuSplat.h)
    };
    /// The shader stage that runs the Walk. Both give the same image.
    enum class WalkShader {
        Fragment, // the back faces of the grid box rasterised: what llvmpipe runs fastest
        Compute   // one invocation per pixel: GPUs like the H100 shade fragments on few of their
                  // multiprocessors but run compute on all
    };

    VotRenderer();
    ~VotRenderer() override;

    /// Replaces the current Vot-Space (copies what it needs; the argument may be freed afterwards).
    void upload(const fit::VotSpace& space);
    bool hasData() const override;
    const SceneBounds& bounds() const override;
    /// [min lower bound, max upper bound] of the polynomials over their boxes (default window).
    std::array<float, 2> valueRange() const override;
    /// [0, log2 of the largest box's geometric-mean edge in cells] (default density window).
    std::array<float, 2> densityRange() const;

    /// RenderMode::Mip or RenderMode::Density.
    FloatImage render(const Camera& camera, int width, int height,
                      const RenderOptions& options = RenderMode::Mip) override;

    /// Cuts every ray of the walk's frames (minip, aip, and mip when the walk draws it) to the cells of
    /// `domain`, exactly: outside it nothing counts, not even background, and the mean divides by the
    /// length inside it; the part outside the grid is dropped. Under mpirun each rank walks its z slab, so
    /// the ranks' frames composite to the whole one (docs/DESIGN.md §12). nullopt (default): the whole
    /// grid, as before. Kept across uploads. A mip the raster strategy draws, and density, refuse a
    /// domain (fit::InputError): they see boxes, not cells.
    void setRayDomain(std::optional<CellDomain> domain);
    const std::optional<CellDomain>& rayDomain() const;
    /// Per pixel, the length in index units of the ray's part that aip divides its integral by (inside
    /// the grid, the domain and the slab), from the walk's own arithmetic, so mean x length is the
    /// integral to a rounding; 0 where the ray misses. Needs a Vot-Space the walk draws, as aip does.
    FloatImage rayLengths(const Camera& camera, int width, int height,
                          const std::optional<Slab>& slab = std::nullopt);

    /// Culling on (default) or off; off draws every Vot in one instanced draw (Raster) or evaluates
    /// every Vot along the ray (Walk); for tests and bench.
    void setCulling(bool enabled);
    /// The MIP strategy asked for (default Splat where the context is a CPU rasteriser, else Walk); takes
    /// effect with the next frame.
    void setStrategy(Strategy strategy);
    Strategy strategy() const;
    /// The strategy MIP frames of the uploaded Vot-Space use: Raster when Walk was asked for but the
    /// space cannot be walked (overlapping boxes, or too large for the GL limits); Splat when asked.
    Strategy mipStrategy() const;
    /// Compute unless the context's renderer is a CPU rasteriser (llvmpipe), which runs Fragment faster
    /// (bench/RESULTS.md). Takes effect with the next frame; Compute where it does not build here falls
    /// back to Fragment with a warning on stderr.
    void setWalkShader(WalkShader shader);
    WalkShader walkShader() const;
    /// Finishes what the first Walk frame of a Vot-Space starts on other threads (the skip boxes that
    /// let later frames step over culled neighbourhoods at once) and applies it now. Frames are
    /// bit-identical before and after, only faster after; benchmarks call this to time the steady state.
    void finishPendingWork();
    const FrameStats& lastFrameStats() const override;
    /// Run first on every thread the renderer starts for work no frame waits for (skip-box growth), so
    /// the caller decides its priority; none by default.
    void setBackgroundThreadStart(std::function<void()> onStart);

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

/// "walk", "raster" or "splat", for /api/stats.
std::string_view strategyName(VotRenderer::Strategy strategy);
/// "fragment" or "compute", for VOTS_WALK_SHADER, render_bench and /api/stats.
std::string_view walkShaderName(VotRenderer::WalkShader shader);
/// The shader named so, or nullopt for any other text.
std::optional<VotRenderer::WalkShader> parseWalkShader(std::string_view name);

} // namespace vots::render
