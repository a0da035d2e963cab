// The walk MIP strategy: its programs, the cell -> Vot grid on the GPU, skip-box growth and its draw.
#pragma once

#include "FloatTarget.h"
#include "GlObjects.h"
#include "SkipBoxes.h"
#include "VotWalkGrid.h"

#include "vots/render/Camera.h"
#include "vots/render/CellDomain.h"
#include "vots/render/FrameStats.h"
#include "vots/render/GpuLayout.h"
#include "vots/render/RenderMode.h"
#include "vots/render/Slab.h"
#include "vots/render/VotRenderer.h"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <vector>

namespace vots::render {

/// Each pixel walks its ray front to back through a grid holding, per cell, the index of the block
/// covering it (a Vot, or an empty block of background), paletted per brick of 16^3 cells and stored
/// only for bricks of more than one block (PalettedCells), with each brick's largest Vot bound; see
/// VotRenderer.h for what is stepped over. Lives on the GL context's thread, like its owner VotRenderer.
class WalkPass {
public:
    using Shader = VotRenderer::WalkShader;

    /// The walk grid of a Vot-Space, built on the CPU before anything reaches GL.
    using Grid = VotWalkGrid;

    WalkPass();
    ~WalkPass();
    WalkPass(const WalkPass&) = delete;
    WalkPass& operator=(const WalkPass&) = delete;

    /// Builds the program for `shader` now, so that a shader this driver refuses shows at once; a
    /// compute walk that does not build falls back to the fragment walk with a warning on stderr.
    void useShader(Shader shader);
    Shader shader() const { return mShader; }
    void setBackgroundThreadStart(std::function<void()> onStart) {
        mBackgroundThreadStart = std::move(onStart);
    }

    /// The grid for `vots` (in their GPU order) on a grid of `dims` points, or nullopt when the walk
    /// cannot draw them: boxes that overlap (the walk sees one Vot per cell), or more than the GL limits
    /// hold.
    static std::optional<Grid> gridFor(const std::vector<GpuVot>& vots, const std::array<int, 3>& dims);
    /// Stops the running skip-box growth (it ends by itself) before a new upload.
    void cancelSkipGrowth();
    /// Uploads the grid (walkable() true), or drops the last one when there is none. votRecords holds
    /// WALK_RECORD_WORDS words per Vot, in the order of `vots`; `background` is what the cells the fit
    /// left out count as in the min and the mean (VotSpace::omittedCellValue()).
    void upload(std::optional<Grid>&& walk, const std::vector<GpuVot>& vots, const std::uint32_t* votRecords,
                float background);
    bool walkable() const { return mWalkable; }

    /// Draws the max, min or mean along each ray (Mip, MinIp, Aip), within the slab if there is one and
    /// the cell domain (nullopt: the whole grid), into the bound target (every pixel is written); culling
    /// off evaluates every Vot on the ray (the mean always does). Counts into `stats`.
    /// `abandoned` (may be empty): RenderOptions::abandoned; throws FrameAbandoned when it says so.
    void draw(RenderMode mode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
              const std::optional<CellDomain>& domain, int width, int height, FloatTarget& target,
              bool culling, FrameStats& stats, const std::function<bool()>& abandoned = {});
    /// Draws, per pixel, the length (index units) of the ray's part the mean divides its integral by:
    /// inside the grid, the domain and the slab, from the mean's own arithmetic; 0 where the ray misses.
    void drawRayLengths(const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                        const std::optional<CellDomain>& domain, int width, int height, FloatTarget& target);
    /// Starts growing the skip boxes of this Vot-Space on another thread, unless it runs or ran.
    void startSkipGrowth();
    /// Puts finished skip boxes into the box table; with `wait`, waits for them first.
    void applySkipBoxes(bool wait);

private:
    // A growth owns its input, so an upload cancels the last one without waiting for it.
    struct SkipGrowth {
        SkipGrowthInput input;
        std::atomic<bool> cancel{false};
    };

    GLuint program(bool compute);
    /// draw() and drawRayLengths(): one walk-shader pass taking `walkMode` (WALK_MODE_*).
    void drawWalk(int walkMode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                  const std::optional<CellDomain>& domain, int width, int height, FloatTarget& target,
                  bool culling, FrameStats& stats, const std::function<bool()>& abandoned);
    void uploadMinAndMeanTables(const std::vector<GpuVot>& vots, const VotWalkGrid& grid,
                                const std::vector<CellBlock>& votBoxes);

    Shader mShader = Shader::Fragment;
    std::array<GlProgram, 2> mPrograms; // fragment and compute, built when first needed
    std::function<void()> mBackgroundThreadStart;
    GlVertexArray mVertexArray = createVertexArray();
    // Buffer textures over their own buffers.
    GlBuffer mCellTableBuffer, mBrickMaxBuffer, mVotBoxBuffer, mWalkRecordBuffer;
    GlTexture mCellTable;  // RGBA32UI: the mixed bricks' packed cell tables (PalettedCells::cellWords)
    GlTexture mBrickMax;   // RGBA32UI per brick, x fastest: the bits of its bound and of the bound ahead
                           // for this frame, its first palette index, its cell table word
    GlTexture mWalkRecord; // RGBA32UI, WALK_RECORD_TEXELS per palette entry (WalkRecord.h): the record of
                           // the Vot it names, zeros for an empty block
    GlTexture mVotBox;     // RGBA32UI per palette entry: the packed box to step over and the bound of the
                           // block the entry names (each brick has its own copies of its blocks' boxes)
    // The same for the min and the mean: each block's own box (skip boxes are grown for the max's
    // bounds, and would step over background the min and the mean must count) and -lowerBound.
    GlBuffer mOwnBoxBuffer;
    GlTexture mOwnBox;
    std::vector<float> mBrickLowNegated; // per brick: max over its blocks of -lowerBound, -background
    float mBackground = -INFINITY;
    std::vector<float> mBrickMaxima;          // per brick: max upperBound of the Vots touching it
    std::vector<std::uint32_t> mPaletteStart; // per brick: its first palette index
    std::vector<std::uint32_t> mCellTableOf;  // per brick: PalettedCells::cellTable
    std::vector<std::uint32_t> mPalette;      // the palette's block ids, to rewrite mVotBox with skip boxes
    std::array<int, 3> mCells{0, 0, 0};
    std::array<int, 3> mBricks{0, 0, 0};
    bool mWalkable = false;
    // Skip boxes (SkipBoxes.h) are grown on another thread once a Vot-Space's first frame is drawn, so
    // they never delay it, and replace the boxes in mVotBox at the next frame: the same images, fewer
    // walk steps.
    std::shared_ptr<SkipGrowth> mSkipGrowth; // this Vot-Space's, until its boxes are in mVotBox
    std::future<std::vector<CellBlock>> mSkipTask;
    std::vector<std::future<std::vector<CellBlock>>> mCancelledSkipTasks; // ending on their own
};

} // namespace vots::render
