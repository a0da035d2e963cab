// The raster strategy: box projection, chunked record bindings, culled MIP batches and the density view.
#include "RasterPass.h"

#include "MaxPyramid.h"
#include "ShaderContract.h"
#include "Shaders.h"
#include "SlabClip.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

namespace {

constexpr std::size_t FIRST_BATCH = 1024; // Vots drawn before the first culling readback
constexpr std::size_t BATCH_GROWTH = 4;   // each later batch considers 4x as many Vots

// Pixel rectangle (GL window coordinates, bottom-up) that may hold the centres of pixels the box
// covers. Returns false when the box covers no pixel; a box crossing the eye plane gets the screen.
bool projectBox(const float m[16], const GpuVot& v, int width, int height, int rect[4]) {
    float base[4], axis[3][4];
    for (int r = 0; r < 4; ++r) {
        base[r] = m[r] * v.lo[0] + m[4 + r] * v.lo[1] + m[8 + r] * v.lo[2] + m[12 + r];
        for (int a = 0; a < 3; ++a)
            axis[a][r] = m[4 * a + r] * (v.hi[a] - v.lo[a]);
    }
    float xMin = INFINITY, xMax = -INFINITY, yMin = INFINITY, yMax = -INFINITY;
    for (int corner = 0; corner < 8; ++corner) {
        float c[4];
        for (int r = 0; r < 4; ++r)
            c[r] = base[r] + ((corner & 1) ? axis[0][r] : 0.f) + ((corner & 2) ? axis[1][r] : 0.f) +
                   ((corner & 4) ? axis[2][r] : 0.f);
        if (!(c[3] > 1e-6f * (std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + 1e-20f))) {
            rect[0] = 0, rect[1] = 0, rect[2] = width - 1, rect[3] = height - 1;
            return true;
        }
        const float x = (c[0] / c[3] * 0.5f + 0.5f) * static_cast<float>(width);
        const float y = (c[1] / c[3] * 0.5f + 0.5f) * static_cast<float>(height);
        xMin = std::min(xMin, x), xMax = std::max(xMax, x), yMin = std::min(yMin, y),
        yMax = std::max(yMax, y);
    }
    // One pixel of margin on each side covers rounding in the rasteriser.
    const float limit = 4.f * MAX_IMAGE_SIDE;
    rect[0] = static_cast<int>(std::floor(std::max(xMin, -limit))) - 1;
    rect[1] = static_cast<int>(std::floor(std::max(yMin, -limit))) - 1;
    rect[2] = static_cast<int>(std::ceil(std::min(xMax, limit))) + 1;
    rect[3] = static_cast<int>(std::ceil(std::min(yMax, limit))) + 1;
    if (rect[2] < 0 || rect[3] < 0 || rect[0] >= width || rect[1] >= height) return false;
    rect[0] = std::max(rect[0], 0), rect[1] = std::max(rect[1], 0);
    rect[2] = std::min(rect[2], width - 1), rect[3] = std::min(rect[3], height - 1);
    return true;
}

} // namespace

RasterPass::RasterPass()
    : mMipProgram(buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_MIP_FRAG, "vot_mip")),
      mDensityProgram(buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_DENSITY_FRAG, "vot_density")) {}

void RasterPass::upload(std::size_t votCount) {
    GLint maxBlock = 0, alignment = 1, maxTexels = 0, textureAlignment = 1;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &textureAlignment);
    std::size_t chunk = std::min(static_cast<std::size_t>(maxBlock) / sizeof(GpuVot),
                                 static_cast<std::size_t>(maxTexels) / VOT_TEXELS);
    const std::size_t alignRecords = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::max(alignment, textureAlignment)) / sizeof(GpuVot));
    chunk -= chunk % alignRecords;
    if (chunk == 0) throw fit::GraphicsError("GL shader storage blocks are too small for one Vot");
    mChunkRecords = chunk;

    mVotBuffer.reset();
    mVisible.assign(std::max<std::size_t>(std::min(votCount, chunk), 1), 0);
    mIndexBuffer = createBuffer();
    glNamedBufferStorage(mIndexBuffer.get(), static_cast<GLsizeiptr>(mVisible.size() * sizeof(std::uint32_t)),
                         nullptr, GL_DYNAMIC_STORAGE_BIT);
    checkGl("VotRenderer upload");
}

void RasterPass::ensureVotBuffer(const std::vector<GpuVot>& vots) {
    if (mVotBuffer.get()) return;
    mVotBuffer = createBuffer();
    glNamedBufferStorage(mVotBuffer.get(),
                         static_cast<GLsizeiptr>(std::max<std::size_t>(vots.size(), 1) * sizeof(GpuVot)),
                         vots.empty() ? nullptr : vots.data(), 0);
    checkGl("VotRenderer records upload");
}

void RasterPass::bindChunk(std::size_t chunk, std::size_t votCount) {
    const std::size_t first = chunk * mChunkRecords;
    // The buffer holds at least one record, so an empty space still binds a valid range.
    const std::size_t count = std::max<std::size_t>(std::min(mChunkRecords, votCount - first), 1);
    const auto offset = static_cast<GLintptr>(first * sizeof(GpuVot));
    const auto bytes = static_cast<GLsizeiptr>(count * sizeof(GpuVot));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, VOT_BUFFER_BINDING, mVotBuffer.get(), offset, bytes);
    glTextureBufferRange(mVotData.get(), GL_RGBA32F, mVotBuffer.get(), offset, bytes);
    glBindTextureUnit(VOT_TEXTURE_UNIT, mVotData.get());
}

void RasterPass::setCommonState(GLuint program, const CameraMatrices& m, int width, int height) {
    glUseProgram(program);
    setMatrixUniform(program, "uIndexToClip", m.indexToClip);
    setMatrixUniform(program, "uClipToIndex", m.clipToIndex);
    glProgramUniform2f(program, glGetUniformLocation(program, "uViewport"), float(width), float(height));
    glBindVertexArray(mVertexArray.get());
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT); // back faces only: one fragment per box and pixel, also from inside a box
    glFrontFace(m.mirrored ? GL_CW : GL_CCW);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, INDEX_BUFFER_BINDING, mIndexBuffer.get());
}

void RasterPass::drawRange(GLuint program, std::size_t first, std::size_t count, bool useList,
                           FrameStats& stats) {
    glProgramUniform1ui(program, glGetUniformLocation(program, "uFirst"), static_cast<GLuint>(first));
    glProgramUniform1i(program, glGetUniformLocation(program, "uUseList"), useList ? 1 : 0);
    glDrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(count));
    ++stats.batches;
}

// Every Vot, chunk by chunk, no culling.
void RasterPass::drawAll(GLuint program, std::size_t votCount, FrameStats& stats) {
    for (std::size_t chunk = 0; chunk * mChunkRecords < votCount; ++chunk) {
        bindChunk(chunk, votCount);
        drawRange(program, 0, std::min(mChunkRecords, votCount - chunk * mChunkRecords), false, stats);
    }
    stats.votsDrawn = votCount;
}

void RasterPass::ensurePrevMax(int width, int height) {
    if (mPrevMax.get() && mPrevMaxWidth == width && mPrevMaxHeight == height) return;
    mPrevMax = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(mPrevMax.get(), 1, GL_R32F, width, height);
    glTextureParameteri(mPrevMax.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(mPrevMax.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    mPrevMaxWidth = width;
    mPrevMaxHeight = height;
}

// Batches in record order (descending bound unless the walk is the MIP strategy); between batches the max
// image is read back, Vots that cannot raise any pixel under their box are skipped, and the rest stop
// early per fragment.
void RasterPass::drawCulled(const CameraMatrices& m, int width, int height, FloatTarget& target,
                            const std::vector<GpuVot>& vots, FrameStats& stats) {
    const GLuint program = mMipProgram.get();
    ensurePrevMax(width, height);
    const float minusInf = -INFINITY;
    glClearTexImage(mPrevMax.get(), 0, GL_RED, GL_FLOAT, &minusInf);
    glBindTextureUnit(PREV_MAX_UNIT, mPrevMax.get());
    glProgramUniform1i(program, glGetUniformLocation(program, "uUsePrevMax"), 1);

    float matrix[16];
    for (int i = 0; i < 16; ++i)
        matrix[i] = static_cast<float>(m.indexToClip[static_cast<std::size_t>(i)]);
    std::vector<float> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    MaxPyramid pyramid;
    bool havePyramid = false;
    std::size_t next = 0, batch = FIRST_BATCH;
    stats.votsDrawn = 0;
    while (next < vots.size()) {
        // A batch stays inside one SSBO chunk; indices in mVisible are relative to the chunk.
        const std::size_t chunk = next / mChunkRecords;
        const std::size_t chunkFirst = chunk * mChunkRecords;
        const std::size_t end = std::min({next + batch, vots.size(), chunkFirst + mChunkRecords});
        std::size_t count = 0;
        for (std::size_t i = next; i < end; ++i) {
            int rect[4];
            if (!projectBox(matrix, vots[i], width, height, rect)) continue;
            if (havePyramid && vots[i].upperBound <= pyramid.minOver(rect[0], rect[1], rect[2], rect[3]))
                continue;
            mVisible[count++] = static_cast<std::uint32_t>(i - chunkFirst);
        }
        if (count > 0) {
            glNamedBufferSubData(mIndexBuffer.get(), 0,
                                 static_cast<GLsizeiptr>(count * sizeof(std::uint32_t)), mVisible.data());
            bindChunk(chunk, vots.size());
            drawRange(program, 0, count, true, stats);
            stats.votsDrawn += count;
        }
        next = end;
        batch *= BATCH_GROWTH;
        if (next < vots.size() && count > 0) {
            glGetTextureImage(target.texture(), 0, GL_RED, GL_FLOAT,
                              static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
            pyramid.build(pixels.data(), width, height);
            havePyramid = true;
            glCopyImageSubData(target.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, mPrevMax.get(), GL_TEXTURE_2D, 0,
                               0, 0, 0, width, height, 1);
        }
    }
}

void RasterPass::draw(RenderMode mode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                      int width, int height, FloatTarget& target, const std::vector<GpuVot>& vots,
                      bool culling, FrameStats& stats) {
    const GLuint program = mode == RenderMode::Mip ? mMipProgram.get() : mDensityProgram.get();
    ensureVotBuffer(vots);
    setCommonState(program, m, width, height);
    if (mode == RenderMode::Mip) {
        setSlabUniforms(program, slab);
        target.clear(-INFINITY);
        glBlendEquation(GL_MAX); // exact for R32F and order-independent: no sorting needed
        if (culling && vots.size() > FIRST_BATCH) {
            drawCulled(m, width, height, target, vots, stats);
        } else {
            glProgramUniform1i(program, glGetUniformLocation(program, "uUsePrevMax"), 0);
            drawAll(program, vots.size(), stats);
        }
    } else {
        target.clear(INFINITY);
        glBlendEquation(GL_MIN);
        drawAll(program, vots.size(), stats);
    }
    glDisable(GL_BLEND);
}

} // namespace vots::render
