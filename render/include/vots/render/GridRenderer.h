// Reference MIP: ray-marches the volume as an R32F 3D texture with trilinear sampling (ground truth,
// baseline).
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/FrameStats.h"
#include "vots/render/Image.h"

#include <array>
#include <memory>

namespace vots::fit {
struct Volume;
}

namespace vots::render {

/// One fullscreen pass per frame: each pixel's ray (same camera maths as VotRenderer) is clipped to
/// the grid box [0, dims-1] in index space and sampled every stepVoxels (default 0.5) index units,
/// plus the exit point; the pixel keeps the maximum. Pixels whose ray misses the grid are -infinity.
/// Needs a current EglContext for its whole life.
class GridRenderer {
public:
    GridRenderer();
    ~GridRenderer();
    GridRenderer(const GridRenderer&) = delete;
    GridRenderer& operator=(const GridRenderer&) = delete;

    /// Uploads the samples as a 3D texture; throws fit::InputError if a side exceeds the GL limit.
    void upload(const fit::Volume& volume);
    bool hasData() const;
    const SceneBounds& bounds() const;
    std::array<float, 2> valueRange() const; // min and max sample

    /// Step along the ray in index units, (0, 0.5]; throws fit::InputError outside.
    void setStepVoxels(float step);
    float stepVoxels() const;

    FloatImage render(const Camera& camera, int width, int height);
    RgbaImage renderRgba(const Camera& camera, int width, int height, const DisplaySettings& display);
    const FrameStats& lastFrameStats() const;

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace vots::render
