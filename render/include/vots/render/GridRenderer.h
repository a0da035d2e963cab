// Exact projections of the trilinear grid (mip, minip, aip): the ground truth the Vot renderer is checked
// against.
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/FrameStats.h"
#include "vots/render/Image.h"
#include "vots/render/Renderer.h"

#include <array>
#include <memory>

namespace vots::fit {
struct Volume;
}

namespace vots::render {

/// One fullscreen pass per z chunk: each pixel's ray (same camera maths as VotRenderer) is clipped to
/// the grid box [0, dims-1] in index space, the near/far planes and the slab, and walked cell by cell;
/// in a cell the trilinear interpolant along the ray is a cubic, whose max, min or integral is exact.
/// aip is the integral over the clipped ray / its length. Pixels whose ray misses the grid (or slab) are
/// -infinity (+infinity for minip). Needs a current EglContext for its whole life.
class GridRenderer final : public Renderer {
public:
    GridRenderer();
    ~GridRenderer() override;

    /// Uploads the samples as 3D textures: one, or chunks of the z range when the depth exceeds the GL
    /// limit or a texture would pass 1 GiB; throws fit::InputError if x or y exceeds the GL limit.
    void upload(const fit::Volume& volume);
    /// Uploads planes [firstPlane, firstPlane + planes.dims z - 1] of the grid `whole` (its grid alone is
    /// read) as chunks that own only the cells between them: rays are clipped to the whole grid as by
    /// upload(whole), and each frame takes the max, min, or the part of the mean, of those planes'
    /// cells alone. Under mpirun each rank draws its z cells this way; max, min or sum over the ranks' frames
    /// is the frame of the whole, as the chunks of one upload combine. Throws fit::InputError as upload.
    void uploadPlanes(const fit::Volume& planes, int firstPlane, const fit::Volume& whole);
    /// What a non-finite sample's cell counts as in minip and aip until the next upload: by default the
    /// uploaded samples' lowest finite one; under mpirun each rank sets the whole volume's, so that the
    /// ranks' frames agree with the one-process frame.
    void useNoDataValue(float value);
    /// The most z planes one texture holds at the next upload (0: from the GL limit and 1 GiB); for
    /// tests, which split small volumes.
    void setChunkPlaneLimit(int planes);
    int chunkCount() const;
    bool hasData() const override;
    const SceneBounds& bounds() const override;
    std::array<float, 2> valueRange() const override; // min and max sample

    /// Mip, MinIp or Aip, with or without a slab; Density needs Vots and throws fit::InputError.
    FloatImage render(const Camera& camera, int width, int height,
                      const RenderOptions& options = RenderMode::Mip) override;
    const FrameStats& lastFrameStats() const override;

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace vots::render
