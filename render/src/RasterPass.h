// The raster strategy: one instanced unit cube per Vot into R32F, MAX-blended in culled batches (MIP) or
// MIN-blended (density).
#pragma once

#include "FloatTarget.h"
#include "GlObjects.h"

#include "vots/render/Camera.h"
#include "vots/render/FrameStats.h"
#include "vots/render/GpuLayout.h"
#include "vots/render/RenderMode.h"
#include "vots/render/Slab.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace vots::render {

/// Draws the Vot records it is given (the owner's `vots`, the same vector at every call between two
/// uploads). With culling, MIP batches go in record order; between batches the max image is read back,
/// a Vot whose bound cannot exceed the smallest max over the pixels its box covers is not drawn, and
/// fragments whose Vot bound is below the pixel's max stop early. Lives on the GL context's thread.
class RasterPass {
public:
    RasterPass();
    RasterPass(const RasterPass&) = delete;
    RasterPass& operator=(const RasterPass&) = delete;

    /// Sizes the chunks a draw binds for `votCount` records (GL_MAX_SHADER_STORAGE_BLOCK_SIZE and the
    /// texture-buffer limit) and drops the last Vot-Space's records; throws fit::GraphicsError when not one
    /// record fits a chunk.
    void upload(std::size_t votCount);
    /// MIP (culled unless `culling` is off or the space is small; clipped to the slab if there is one)
    /// or density into the bound target.
    void draw(RenderMode mode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab, int width,
              int height, FloatTarget& target, const std::vector<GpuVot>& vots, bool culling,
              FrameStats& stats);

private:
    void ensureVotBuffer(const std::vector<GpuVot>& vots);
    void bindChunk(std::size_t chunk, std::size_t votCount);
    void setCommonState(GLuint program, const CameraMatrices& m, int width, int height);
    void drawRange(GLuint program, std::size_t first, std::size_t count, bool useList, FrameStats& stats);
    void drawAll(GLuint program, std::size_t votCount, FrameStats& stats);
    void ensurePrevMax(int width, int height);
    void drawCulled(const CameraMatrices& m, int width, int height, FloatTarget& target,
                    const std::vector<GpuVot>& vots, FrameStats& stats);

    GlProgram mMipProgram;
    GlProgram mDensityProgram;
    GlVertexArray mVertexArray = createVertexArray();
    GlBuffer mVotBuffer; // the records, made by the first frame that draws (most spaces are only walked)
    GlBuffer mIndexBuffer;
    GlTexture mVotData = createTexture(GL_TEXTURE_BUFFER); // RGBA32F view of the bound chunk (uVotData)
    GlTexture mPrevMax; // copy of the max image after the last batch, same size as the target
    int mPrevMaxWidth = 0, mPrevMaxHeight = 0;
    std::vector<std::uint32_t> mVisible; // the batch's Vots to draw, relative to their chunk
    std::size_t mChunkRecords = 1;       // Vots per SSBO binding
};

} // namespace vots::render
