// Reference MIP: fullscreen ray march through R32F 3D textures of the volume (trilinear, fixed step).
#include "vots/render/GridRenderer.h"

#include "DisplayPass.h"
#include "FloatTarget.h"
#include "FrameReadout.h"
#include "GlObjects.h"
#include "Shaders.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"
#include "vots/render/Error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

namespace vots::render {

namespace {

// One 3D texture's share of the z range. Textures overlap by a plane beyond the range they sample on
// either side, so every sample they take interpolates between planes they hold.
struct Slab {
    GlTexture texture;
    int firstPlane = 0; // the grid z of the texture's plane 0
    int planes = 0;
    float zLo = -INFINITY, zHi = INFINITY; // the samples it takes; all when there is one slab
};

// A texture of more bytes than this is split too: llvmpipe and drivers fail on huge textures well
// before they run out of memory, and a frame's slabs are drawn one after another anyway.
constexpr std::size_t MAX_SLAB_BYTES = std::size_t{1} << 30;

} // namespace

struct GridRenderer::Impl {
    GlProgram program = buildProgram(shaders::FULLSCREEN_VERT, shaders::GRID_MIP_FRAG, "grid_mip");
    GlVertexArray vertexArray = createVertexArray();
    std::vector<Slab> slabs;
    int slabPlaneLimit = 0; // 0: from the GL limit and MAX_SLAB_BYTES
    FloatTarget target;
    DisplayPass display;
    bool hasData = false;
    SceneBounds bounds;
    std::array<float, 2> valueRange{0.f, 0.f};
    float step = 0.5f;
    FrameStats stats;

    void draw(const Camera& camera, int width, int height) {
        if (!hasData) throw RenderError("GridRenderer: render() before upload()");
        const CameraMatrices m = computeCameraMatrices(camera, bounds, width, height);
        const auto t0 = FrameClock::now();
        stats = FrameStats{};
        target.bind(width, height);
        target.clear(-INFINITY);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_DEPTH_TEST);
        const GLuint p = program.get();
        glUseProgram(p);
        setMatrixUniform(p, "uClipToIndex", m.clipToIndex);
        glProgramUniform2f(p, glGetUniformLocation(p, "uViewport"), float(width), float(height));
        glProgramUniform3f(p, glGetUniformLocation(p, "uDims"), float(bounds.dims[0]), float(bounds.dims[1]),
                           float(bounds.dims[2]));
        glProgramUniform1f(p, glGetUniformLocation(p, "uStep"), step);
        glProgramUniform1i(p, glGetUniformLocation(p, "uVolume"), 0);
        glBindVertexArray(vertexArray.get());
        if (slabs.size() > 1) { // each slab's max of its samples; the frame is the max of those
            glEnable(GL_BLEND);
            glBlendEquation(GL_MAX);
        }
        for (const Slab& slab : slabs) {
            glProgramUniform3f(p, glGetUniformLocation(p, "uSlabOrigin"), 0.f, 0.f, float(slab.firstPlane));
            glProgramUniform3f(p, glGetUniformLocation(p, "uSlabDims"), float(bounds.dims[0]),
                               float(bounds.dims[1]), float(slab.planes));
            glProgramUniform2f(p, glGetUniformLocation(p, "uSlabZ"), slabs.size() > 1 ? slab.zLo : -2e30f,
                               slab.zHi);
            glBindTextureUnit(0, slab.texture.get());
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        glDisable(GL_BLEND);
        stats.batches = static_cast<int>(slabs.size());
        glFinish();
        stats.gpuMs = msSince(t0);
        checkGl("GridRenderer draw");
    }
};

GridRenderer::GridRenderer() : mImpl(std::make_unique<Impl>()) {}
GridRenderer::~GridRenderer() = default;

void GridRenderer::upload(const fit::Volume& volume) {
    Impl& d = *mImpl;
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
    for (int a = 0; a < 3; ++a)
        if (volume.dims[a] < 2 || (a < 2 && volume.dims[a] > maxSide))
            throw fit::InputError("volume side " + std::to_string(volume.dims[a]) + " outside 2.." +
                                  std::to_string(maxSide) + " for the reference renderer");
    if (volume.values.size() != volume.sampleCount())
        throw fit::InputError("volume has the wrong number of samples");
    const std::size_t planeSamples =
        static_cast<std::size_t>(volume.dims[0]) * static_cast<std::size_t>(volume.dims[1]);
    int planeLimit =
        d.slabPlaneLimit > 0
            ? d.slabPlaneLimit
            : static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(maxSide),
                                                     MAX_SLAB_BYTES / (planeSamples * sizeof(float))));
    if (planeLimit < 4)
        throw fit::InputError("volume planes too large for the reference renderer's textures");
    // Slab k samples z in [k P, (k + 1) P] and holds the planes one beyond on either side.
    const int depth = volume.dims[2];
    const int owned = planeLimit - 3;
    std::vector<Slab> slabs;
    if (depth <= planeLimit) {
        slabs.push_back(Slab{{}, 0, depth});
    } else {
        for (int z = 0; z < depth - 1; z += owned) {
            Slab slab;
            slab.firstPlane = std::max(0, z - 1);
            const int lastPlane = std::min(depth - 1, z + owned + 1);
            slab.planes = lastPlane - slab.firstPlane + 1;
            slab.zLo = float(z);
            slab.zHi = float(std::min(depth - 1, z + owned));
            slabs.push_back(std::move(slab));
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (Slab& slab : slabs) {
        slab.texture = createTexture(GL_TEXTURE_3D);
        const GLuint t = slab.texture.get();
        glTextureStorage3D(t, 1, GL_R32F, volume.dims[0], volume.dims[1], slab.planes);
        glTextureSubImage3D(t, 0, 0, 0, 0, volume.dims[0], volume.dims[1], slab.planes, GL_RED, GL_FLOAT,
                            volume.values.data() + static_cast<std::size_t>(slab.firstPlane) * planeSamples);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(t, wrap, GL_CLAMP_TO_EDGE);
        checkGl("GridRenderer upload");
    }
    d.slabs = std::move(slabs);
    d.bounds = sceneBounds(volume);
    d.valueRange = volume.valueRange();
    d.hasData = true;
}

void GridRenderer::setSlabPlaneLimit(int planes) {
    if (planes != 0 && planes < 4) throw fit::InputError("slab plane limit must be 0 or at least 4");
    mImpl->slabPlaneLimit = planes;
}
int GridRenderer::slabCount() const {
    return static_cast<int>(mImpl->slabs.size());
}

bool GridRenderer::hasData() const {
    return mImpl->hasData;
}
const SceneBounds& GridRenderer::bounds() const {
    return mImpl->bounds;
}
std::array<float, 2> GridRenderer::valueRange() const {
    return mImpl->valueRange;
}

void GridRenderer::setStepVoxels(float step) {
    if (!(step > 0.f && step <= 0.5f)) throw fit::InputError("reference step must be in (0, 0.5] voxels");
    mImpl->step = step;
}
float GridRenderer::stepVoxels() const {
    return mImpl->step;
}
const FrameStats& GridRenderer::lastFrameStats() const {
    return mImpl->stats;
}

namespace {
void checkGridMode(RenderMode mode) {
    if (mode == RenderMode::Density)
        throw fit::InputError("GridRenderer draws the grid's MIP (reference); density needs a Vot-Space");
}
} // namespace

FloatImage GridRenderer::render(const Camera& camera, int width, int height, RenderMode mode) {
    checkGridMode(mode);
    mImpl->draw(camera, width, height);
    return readFloatFrame(mImpl->target, mImpl->stats);
}

RgbaImage GridRenderer::renderRgba(const Camera& camera, int width, int height,
                                   const DisplaySettings& display, RenderMode mode) {
    checkGridMode(mode);
    mImpl->draw(camera, width, height);
    return readDisplayedFrame(mImpl->display, mImpl->target, display, mImpl->stats);
}

} // namespace vots::render
