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
struct Chunk {
    GlTexture texture;
    int firstPlane = 0; // the grid z of the texture's plane 0
    int planes = 0;
    float zLo = -INFINITY, zHi = INFINITY; // the samples it takes; all when there is one chunk
};

// A texture of more bytes than this is split too: llvmpipe and drivers fail on huge textures well
// before they run out of memory, and a frame's chunks are drawn one after another anyway.
constexpr std::size_t MAX_CHUNK_BYTES = std::size_t{1} << 30;

} // namespace

struct GridRenderer::Impl {
    GlProgram program = buildProgram(shaders::FULLSCREEN_VERT, shaders::GRID_MIP_FRAG, "grid_mip");
    GlVertexArray vertexArray = createVertexArray();
    std::vector<Chunk> chunks;
    int chunkPlaneLimit = 0; // 0: from the GL limit and MAX_CHUNK_BYTES
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
        if (chunks.size() > 1) { // each chunk's max of its samples; the frame is the max of those
            glEnable(GL_BLEND);
            glBlendEquation(GL_MAX);
        }
        for (const Chunk& chunk : chunks) {
            glProgramUniform3f(p, glGetUniformLocation(p, "uChunkOrigin"), 0.f, 0.f, float(chunk.firstPlane));
            glProgramUniform3f(p, glGetUniformLocation(p, "uChunkDims"), float(bounds.dims[0]),
                               float(bounds.dims[1]), float(chunk.planes));
            glProgramUniform2f(p, glGetUniformLocation(p, "uChunkZ"), chunks.size() > 1 ? chunk.zLo : -2e30f,
                               chunk.zHi);
            glBindTextureUnit(0, chunk.texture.get());
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        glDisable(GL_BLEND);
        stats.batches = static_cast<int>(chunks.size());
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
        d.chunkPlaneLimit > 0
            ? d.chunkPlaneLimit
            : static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(maxSide),
                                                     MAX_CHUNK_BYTES / (planeSamples * sizeof(float))));
    if (planeLimit < 4)
        throw fit::InputError("volume planes too large for the reference renderer's textures");
    // Chunk k samples z in [k P, (k + 1) P] and holds the planes one beyond on either side.
    const int depth = volume.dims[2];
    const int owned = planeLimit - 3;
    std::vector<Chunk> chunks;
    if (depth <= planeLimit) {
        chunks.push_back(Chunk{{}, 0, depth});
    } else {
        for (int z = 0; z < depth - 1; z += owned) {
            Chunk chunk;
            chunk.firstPlane = std::max(0, z - 1);
            const int lastPlane = std::min(depth - 1, z + owned + 1);
            chunk.planes = lastPlane - chunk.firstPlane + 1;
            chunk.zLo = float(z);
            chunk.zHi = float(std::min(depth - 1, z + owned));
            chunks.push_back(std::move(chunk));
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (Chunk& chunk : chunks) {
        chunk.texture = createTexture(GL_TEXTURE_3D);
        const GLuint t = chunk.texture.get();
        glTextureStorage3D(t, 1, GL_R32F, volume.dims[0], volume.dims[1], chunk.planes);
        glTextureSubImage3D(t, 0, 0, 0, 0, volume.dims[0], volume.dims[1], chunk.planes, GL_RED, GL_FLOAT,
                            volume.values.data() + static_cast<std::size_t>(chunk.firstPlane) * planeSamples);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
            glTextureParameteri(t, wrap, GL_CLAMP_TO_EDGE);
        checkGl("GridRenderer upload");
    }
    d.chunks = std::move(chunks);
    d.bounds = sceneBounds(volume);
    d.valueRange = volume.valueRange();
    d.hasData = true;
}

void GridRenderer::setChunkPlaneLimit(int planes) {
    if (planes != 0 && planes < 4) throw fit::InputError("chunk plane limit must be 0 or at least 4");
    mImpl->chunkPlaneLimit = planes;
}
int GridRenderer::chunkCount() const {
    return static_cast<int>(mImpl->chunks.size());
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
void checkGridMode(const RenderOptions& options) {
    if (options.mode == RenderMode::Density)
        throw fit::InputError("the grid renderer draws mip, minip and aip; density needs a Vot-Space");
    if (options.mode != RenderMode::Mip)
        throw fit::InputError("the grid renderer does not draw " + std::string(renderModeName(options.mode)) +
                              " yet");
    if (options.slab) throw fit::InputError("the grid renderer does not clip to a slab yet");
}
} // namespace

FloatImage GridRenderer::render(const Camera& camera, int width, int height, const RenderOptions& options) {
    checkGridMode(options);
    mImpl->draw(camera, width, height);
    return readFloatFrame(mImpl->target, mImpl->stats);
}

RgbaImage GridRenderer::renderRgba(const Camera& camera, int width, int height,
                                   const DisplaySettings& display, const RenderOptions& options) {
    checkGridMode(options);
    mImpl->draw(camera, width, height);
    return readDisplayedFrame(mImpl->display, mImpl->target, display, mImpl->stats);
}

} // namespace vots::render
