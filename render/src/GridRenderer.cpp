// Reference MIP: fullscreen ray march through the R32F 3D texture of the volume (trilinear, fixed step).
#include "vots/render/GridRenderer.h"

#include "DisplayPass.h"
#include "FloatTarget.h"
#include "FrameReadout.h"
#include "GlObjects.h"
#include "Shaders.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"
#include "vots/render/Error.h"

#include <chrono>
#include <cmath>
#include <string>

namespace vots::render {

struct GridRenderer::Impl {
    GlProgram program = buildProgram(shaders::FULLSCREEN_VERT, shaders::GRID_MIP_FRAG, "grid_mip");
    GlVertexArray vertexArray = createVertexArray();
    GlTexture volume;
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
        glBindTextureUnit(0, volume.get());
        glBindVertexArray(vertexArray.get());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        stats.batches = 1;
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
        if (volume.dims[a] < 2 || volume.dims[a] > maxSide)
            throw fit::InputError("volume side " + std::to_string(volume.dims[a]) + " outside 2.." +
                                  std::to_string(maxSide) + " for the reference renderer");
    if (volume.values.size() != volume.sampleCount())
        throw fit::InputError("volume has the wrong number of samples");
    d.volume = createTexture(GL_TEXTURE_3D);
    glTextureStorage3D(d.volume.get(), 1, GL_R32F, volume.dims[0], volume.dims[1], volume.dims[2]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage3D(d.volume.get(), 0, 0, 0, 0, volume.dims[0], volume.dims[1], volume.dims[2], GL_RED,
                        GL_FLOAT, volume.values.data());
    glTextureParameteri(d.volume.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(d.volume.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTextureParameteri(d.volume.get(), wrap, GL_CLAMP_TO_EDGE);
    checkGl("GridRenderer upload");
    d.bounds = sceneBounds(volume);
    d.valueRange = volume.valueRange();
    d.hasData = true;
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
