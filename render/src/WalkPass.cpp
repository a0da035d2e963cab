// The walk MIP strategy: grid upload, box table, skip-box growth on another thread, and the walk's draw.
#include "WalkPass.h"

#include "BrickAhead.h"
#include "FrameReadout.h"
#include "ParallelChunks.h"
#include "ShaderContract.h"
#include "Shaders.h"
#include "SlabClip.h"
#include "WalkRecord.h"

#include "vots/fit/Error.h"
#include "vots/render/EglContext.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>

namespace vots::render {

namespace {

constexpr int WALK_BRICK_SHIFT = 4; // bricks of 16^3 cells (bench/RESULTS.md compares 8, 16, 32)

// An abandonable frame's bands: about eight, each of whole rows of llvmpipe's 64-pixel tiles, so that its
// rasterizer threads still share full rows of tiles and a band costs about an eighth of the frame. A frame
// of fewer tile rows than that (a drag's draft) is one band: bands of a row or two leave the threads short
// of tiles (6-19 % slower at 256-320 rows, bench/RESULTS.md), and such a frame lasts about a still's band.
constexpr int WALK_BANDS = 8;
constexpr int TILE_SIDE = 64;
int walkBandRows(int height) {
    if (height < WALK_BANDS * TILE_SIDE) return height;
    const int rows = (height + WALK_BANDS - 1) / WALK_BANDS;
    return (rows + TILE_SIDE - 1) / TILE_SIDE * TILE_SIDE;
}

// One RGBA32UI walk texel: box corners in 16 bits each, and the bound's bits.
void packBox(std::uint32_t* texel, const std::array<int, 3>& lo, const std::array<int, 3>& hi, float bound) {
    packBoxCorners(texel, lo, hi);
    std::memcpy(&texel[3], &bound, sizeof(float));
}

// The walk's box table: per palette entry, the box boxOf(block) of the block it names, Vots first, and
// that block's bound (-inf for an empty block). Entries naming no block stay zero.
template <class BoxOf>
std::vector<std::uint32_t> boxTable(const std::vector<std::uint32_t>& palette,
                                    const std::vector<float>& votBounds, std::size_t blockCount,
                                    BoxOf boxOf) {
    std::vector<std::uint32_t> texels(4 * palette.size(), 0);
    for (std::size_t i = 0; i < palette.size(); ++i) {
        const std::uint32_t block = palette[i];
        if (block >= blockCount) continue;
        const CellBlock& box = boxOf(block);
        packBox(&texels[4 * i], box.lo, box.hi, block < votBounds.size() ? votBounds[block] : -INFINITY);
    }
    return texels;
}

// What a background cell contributes in a walk mode (uEmptyValue of vot_walk.glsl): nothing to the max;
// the background value to the min (negated, as the min is walked) and to the mean. A space fitted with
// no background threshold has no background cells.
float emptyValueFor(int walkMode, float background) {
    if (walkMode == WALK_MODE_MIN) return std::isfinite(background) ? -background : -INFINITY;
    if (walkMode == WALK_MODE_MEAN) return std::isfinite(background) ? background : 0.f;
    return -INFINITY;
}

// A buffer texture over a new buffer holding `bytes` of `data` (nullptr: written later).
void bufferTexture(GlBuffer& buffer, GlTexture& texture, GLenum format, const void* data, std::size_t bytes) {
    buffer = createBuffer();
    glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_STORAGE_BIT);
    texture = createTexture(GL_TEXTURE_BUFFER);
    glTextureBuffer(texture.get(), format, buffer.get());
}

// The compute walk spreads over all of a GPU's multiprocessors; a CPU rasteriser runs the fragment walk
// faster (bench/RESULTS.md, "GPU").
VotRenderer::WalkShader defaultShader() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return renderer && EglContext::isSoftwareRenderer(renderer) ? VotRenderer::WalkShader::Fragment
                                                                : VotRenderer::WalkShader::Compute;
}

} // namespace

WalkPass::WalkPass() {
    useShader(defaultShader());
}

WalkPass::~WalkPass() {
    if (mSkipGrowth) mSkipGrowth->cancel = true;
    for (auto& task : mCancelledSkipTasks)
        task.wait();
}

GLuint WalkPass::program(bool compute) {
    GlProgram& program = mPrograms[compute ? 1 : 0];
    if (!program.get())
        program = compute ? buildComputeProgram(shaders::VOT_WALK_COMP, "vot_walk_compute")
                          : buildProgram(shaders::WALK_BOX_VERT, shaders::VOT_WALK_FRAG, "vot_walk");
    return program.get();
}

void WalkPass::useShader(Shader shader) {
    // The fragment walk is the one every driver has run.
    if (shader == Shader::Compute) {
        try {
            program(true);
            mShader = shader;
            return;
        } catch (const fit::GraphicsError& e) {
            std::cerr << "vots: warning: the compute walk does not build here, using the fragment walk: "
                      << e.what() << "\n";
        }
    }
    program(false);
    mShader = Shader::Fragment;
}

void WalkPass::cancelSkipGrowth() {
    if (mSkipTask.valid()) {
        mSkipGrowth->cancel = true;
        mCancelledSkipTasks.push_back(std::move(mSkipTask));
    }
    mSkipGrowth.reset();
    std::erase_if(mCancelledSkipTasks, [](const std::future<std::vector<CellBlock>>& task) {
        return task.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    });
}

void WalkPass::startSkipGrowth() {
    if (!mSkipGrowth || mSkipTask.valid()) return;
    mSkipTask = std::async(std::launch::async, [growth = mSkipGrowth, onStart = mBackgroundThreadStart] {
        // The caller's priority policy; the growth's worker threads inherit what it sets.
        if (onStart) onStart();
        return growSkipBoxes(growth->input, growth->cancel);
    });
}

void WalkPass::applySkipBoxes(bool wait) {
    if (!mSkipTask.valid()) return;
    if (!wait && mSkipTask.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    const SkipGrowthInput& in = mSkipGrowth->input;
    std::vector<CellBlock> grown;
    try {
        grown = mSkipTask.get();
    } catch (const std::exception&) {
        // Out of memory, say: the Vots' own boxes stay, which are exact too, only slower.
    }
    mSkipTask = {};
    if (grown.size() == in.votBounds.size() + in.grid.emptyBlocks.size()) {
        const std::vector<std::uint32_t> texels =
            boxTable(mPalette, in.votBounds, grown.size(),
                     [&](std::uint32_t block) -> const CellBlock& { return grown[block]; });
        glNamedBufferSubData(mVotBoxBuffer.get(), 0,
                             static_cast<GLsizeiptr>(texels.size() * sizeof(std::uint32_t)), texels.data());
        checkGl("VotRenderer skip boxes");
    }
    mSkipGrowth.reset();
}

std::optional<WalkPass::Grid> WalkPass::gridFor(const std::vector<GpuVot>& vots,
                                                const std::array<int, 3>& dims) {
    for (int a = 0; a < 3; ++a)
        if (dims[a] - 1 > 0xffff) return std::nullopt; // box corners are packed in 16 bits
    std::optional<VotWalkGrid> grid = buildVotWalkGrid(vots, dims, WALK_BRICK_SHIFT, nullptr);
    if (!grid) return std::nullopt;
    const PalettedCells& cells = grid->index;
    GLint maxTexels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
    const std::size_t cellTexels = cells.cellWords.size() / 4;
    if (cells.cellWords.size() >= MAX_CELL_WORDS ||
        std::max(cellTexels, WALK_RECORD_TEXELS * cells.palette.size()) >=
            static_cast<std::size_t>(maxTexels))
        return std::nullopt;
    return grid;
}

void WalkPass::upload(std::optional<Grid>&& walk, const std::vector<GpuVot>& vots,
                      const std::uint32_t* votRecords, float background) {
    mWalkable = false;
    for (GlTexture* t : {&mCellTable, &mBrickMax, &mVotBox, &mOwnBox, &mWalkRecord})
        t->reset();
    for (GlBuffer* b :
         {&mCellTableBuffer, &mBrickMaxBuffer, &mVotBoxBuffer, &mOwnBoxBuffer, &mWalkRecordBuffer})
        b->reset();
    mBrickLowNegated.clear();
    mBackground = background;
    if (!walk) return;
    VotWalkGrid* grid = &*walk;
    const PalettedCells& cells = grid->index;
    const std::size_t blocks = vots.size() + grid->emptyBlocks.size();

    // What the skip-box growth will read; the Vots' own boxes are also the first box table.
    mSkipGrowth = std::make_shared<SkipGrowth>();
    SkipGrowthInput& in = mSkipGrowth->input;
    in.votBoxes.resize(vots.size());
    in.votBounds.resize(vots.size());
    for (std::size_t i = 0; i < vots.size(); ++i) {
        in.votBoxes[i] = cellBlockOf(vots[i]);
        in.votBounds[i] = vots[i].upperBound;
    }

    // One RGBA32UI texel per palette entry, the box and bound of the block it names (bound -inf for an
    // empty block): a step reads it straight after the cell, and a brick's entries share cache lines,
    // where one table by block index would cost another dependent read per step.
    const std::vector<std::uint32_t> boxes =
        boxTable(cells.palette, in.votBounds, blocks, [&](std::uint32_t block) -> const CellBlock& {
            return block < vots.size() ? in.votBoxes[block] : grid->emptyBlocks[block - vots.size()];
        });

    bufferTexture(mCellTableBuffer, mCellTable, GL_RGBA32UI, cells.cellWords.data(),
                  cells.cellWords.size() * sizeof(std::uint32_t));
    mBrickMaxima = grid->brickMax;
    mPaletteStart = cells.paletteStart;
    mCellTableOf = cells.cellTable;
    mPalette = cells.palette;
    // Written by every frame before it draws: the bounds ahead depend on the view.
    bufferTexture(mBrickMaxBuffer, mBrickMax, GL_RGBA32UI, nullptr,
                  4 * mBrickMaxima.size() * sizeof(std::uint32_t));
    bufferTexture(mVotBoxBuffer, mVotBox, GL_RGBA32UI, boxes.data(), boxes.size() * sizeof(std::uint32_t));
    uploadMinAndMeanTables(vots, *grid, in.votBoxes);
    // Walk records by palette entry, like the box table: a step that evaluates reads the record straight
    // after the box, with no lookup of the Vot's index between them; a Vot in two bricks has two copies,
    // entries of empty blocks stay zero. Written straight into the mapped buffer, since a copy of our
    // own would cost as much again; at least one record, so that an empty space binds a valid buffer.
    const std::size_t recordBytes = WALK_RECORD_WORDS * sizeof(std::uint32_t);
    const std::size_t entries = std::max<std::size_t>(mPalette.size(), 1);
    mWalkRecordBuffer = createBuffer();
    glNamedBufferStorage(mWalkRecordBuffer.get(), static_cast<GLsizeiptr>(entries * recordBytes), nullptr,
                         GL_MAP_WRITE_BIT);
    auto* mapped = static_cast<std::uint32_t*>(
        glMapNamedBufferRange(mWalkRecordBuffer.get(), 0, static_cast<GLsizeiptr>(entries * recordBytes),
                              GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT));
    if (!mapped) throw fit::GraphicsError("VotRenderer: could not map the walk records for writing");
    parallelChunks(entries, [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i) {
            std::uint32_t* out = mapped + i * WALK_RECORD_WORDS;
            if (i < mPalette.size() && mPalette[i] < vots.size())
                std::copy_n(&votRecords[mPalette[i] * WALK_RECORD_WORDS], WALK_RECORD_WORDS, out);
            else
                std::fill_n(out, WALK_RECORD_WORDS, 0u);
        }
    });
    glUnmapNamedBuffer(mWalkRecordBuffer.get());
    mWalkRecord = createTexture(GL_TEXTURE_BUFFER);
    glTextureBuffer(mWalkRecord.get(), GL_RGBA32UI, mWalkRecordBuffer.get());
    checkGl("VotRenderer walk grid upload");
    mCells = grid->cells;
    mBricks = grid->bricks;
    in.grid = std::move(*grid);
    mWalkable = true;
}

void WalkPass::uploadMinAndMeanTables(const std::vector<GpuVot>& vots, const VotWalkGrid& grid,
                                      const std::vector<CellBlock>& votBoxes) {
    const PalettedCells& cells = grid.index;
    std::vector<float> lowNegated(vots.size());
    for (std::size_t i = 0; i < vots.size(); ++i)
        lowNegated[i] = -vots[i].lowerBound;
    const std::vector<std::uint32_t> own =
        boxTable(cells.palette, lowNegated, vots.size() + grid.emptyBlocks.size(),
                 [&](std::uint32_t block) -> const CellBlock& {
                     return block < vots.size() ? votBoxes[block] : grid.emptyBlocks[block - vots.size()];
                 });
    bufferTexture(mOwnBoxBuffer, mOwnBox, GL_RGBA32UI, own.data(), own.size() * sizeof(std::uint32_t));
    // A brick's bound for the min covers its background cells too: they count as the background value.
    const float emptyNegated = emptyValueFor(WALK_MODE_MIN, mBackground);
    const std::size_t brickCount = cells.paletteStart.size();
    mBrickLowNegated.assign(brickCount, -INFINITY);
    for (std::size_t b = 0; b < brickCount; ++b) {
        const std::size_t end = b + 1 < brickCount ? cells.paletteStart[b + 1] : cells.palette.size();
        for (std::size_t i = cells.paletteStart[b]; i < end; ++i) {
            const std::uint32_t block = cells.palette[i];
            mBrickLowNegated[b] =
                std::max(mBrickLowNegated[b], block < vots.size() ? lowNegated[block] : emptyNegated);
        }
    }
}

void WalkPass::draw(RenderMode mode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                    const std::optional<CellDomain>& domain, int width, int height, FloatTarget& target,
                    bool culling, FrameStats& stats, const std::function<bool()>& abandoned) {
    const int walkMode = mode == RenderMode::MinIp ? WALK_MODE_MIN
                         : mode == RenderMode::Aip ? WALK_MODE_MEAN
                                                   : WALK_MODE_MAX;
    drawWalk(walkMode, m, slab, domain, width, height, target, culling, stats, abandoned);
}

void WalkPass::drawRayLengths(const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                              const std::optional<CellDomain>& domain, int width, int height,
                              FloatTarget& target) {
    FrameStats unused;
    drawWalk(WALK_MODE_LENGTH, m, slab, domain, width, height, target, false, unused, {});
}

void WalkPass::drawWalk(int walkMode, const CameraMatrices& m, const std::optional<SlabPlanes>& slab,
                        const std::optional<CellDomain>& domain, int width, int height, FloatTarget& target,
                        bool culling, FrameStats& stats, const std::function<bool()>& abandoned) {
    applySkipBoxes(false);
    // What no ray takes anything from: -inf, or for the length 0.
    const float nothing = walkMode == WALK_MODE_LENGTH ? 0.f : -INFINITY;
    const CellDomain cells = domainInGrid(domain, mCells);
    if (cells.empty()) { // every ray misses it
        target.clear(nothing);
        stats.batches = 1;
        stats.votsDrawn = 0;
        return;
    }
    const float emptyValue = emptyValueFor(walkMode, mBackground);
    const std::vector<float>& brickBound = walkMode == WALK_MODE_MIN ? mBrickLowNegated : mBrickMaxima;
    const bool compute = mShader == Shader::Compute;
    const GLuint p = program(compute);
    glUseProgram(p);
    setMatrixUniform(p, "uIndexToClip", m.indexToClip);
    setMatrixUniform(p, "uClipToIndex", m.clipToIndex);
    glProgramUniform2f(p, glGetUniformLocation(p, "uViewport"), float(width), float(height));
    glProgramUniform3f(p, glGetUniformLocation(p, "uBoxLo"), -BOX_SLACK, -BOX_SLACK, -BOX_SLACK);
    glProgramUniform3f(p, glGetUniformLocation(p, "uBoxHi"), float(mCells[0]) + BOX_SLACK,
                       float(mCells[1]) + BOX_SLACK, float(mCells[2]) + BOX_SLACK);
    glProgramUniform3i(p, glGetUniformLocation(p, "uCells"), mCells[0], mCells[1], mCells[2]);
    glProgramUniform3i(p, glGetUniformLocation(p, "uBricks"), mBricks[0], mBricks[1], mBricks[2]);
    glProgramUniform1i(p, glGetUniformLocation(p, "uBrickShift"), WALK_BRICK_SHIFT);
    // The mean takes every Vot on the ray: nothing can be culled.
    const bool cull = culling && walkMode != WALK_MODE_MEAN;
    glProgramUniform1i(p, glGetUniformLocation(p, "uCull"), cull ? 1 : 0);
    glProgramUniform1i(p, glGetUniformLocation(p, "uMode"), walkMode);
    glProgramUniform1f(p, glGetUniformLocation(p, "uEmptyValue"), emptyValue);
    glProgramUniform3i(p, glGetUniformLocation(p, "uDomainLo"), cells.lo[0], cells.lo[1], cells.lo[2]);
    glProgramUniform3i(p, glGetUniformLocation(p, "uDomainHi"), cells.hi[0], cells.hi[1], cells.hi[2]);
    const bool wholeGrid = cells.lo == std::array<int, 3>{0, 0, 0} && cells.hi == mCells;
    glProgramUniform1i(p, glGetUniformLocation(p, "uDomainClips"), wholeGrid ? 0 : 1);
    setSlabUniforms(p, slab);
    // The bounds ahead depend on the view, so they are recomputed per frame (linear in the bricks).
    const auto aheadStart = FrameClock::now();
    const std::vector<float> ahead =
        cull ? brickMaximaAhead({mCells, mBricks, WALK_BRICK_SHIFT}, brickBound, rayFamilyOf(m.clipToIndex))
             : std::vector<float>(brickBound.size(), INFINITY);
    stats.boundsAheadMs = msSince(aheadStart);
    // (bound, bound ahead, palette start, cell table) per brick
    std::vector<std::uint32_t> brickBounds(4 * ahead.size());
    for (std::size_t i = 0; i < ahead.size(); ++i) {
        brickBounds[4 * i] = std::bit_cast<std::uint32_t>(brickBound[i]);
        brickBounds[4 * i + 1] = std::bit_cast<std::uint32_t>(ahead[i]);
        brickBounds[4 * i + 2] = mPaletteStart[i];
        brickBounds[4 * i + 3] = mCellTableOf[i];
    }
    glNamedBufferSubData(mBrickMaxBuffer.get(), 0,
                         static_cast<GLsizeiptr>(brickBounds.size() * sizeof(std::uint32_t)),
                         brickBounds.data());
    glBindTextureUnit(WALK_CELL_TABLE_UNIT, mCellTable.get());
    glBindTextureUnit(WALK_BRICK_MAX_UNIT, mBrickMax.get());
    glBindTextureUnit(WALK_VOT_BOX_UNIT, walkMode == WALK_MODE_MAX ? mVotBox.get() : mOwnBox.get());
    glBindTextureUnit(WALK_RECORD_UNIT, mWalkRecord.get());
    stats.batches = 1;
    stats.votsDrawn = 0;
    if (compute) {
        constexpr auto GROUP_SIDE = static_cast<GLuint>(WALK_GROUP_SIDE);
        glBindImageTexture(WALK_TARGET_IMAGE_UNIT, target.texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glDispatchCompute((static_cast<GLuint>(width) + GROUP_SIDE - 1) / GROUP_SIDE,
                          (static_cast<GLuint>(height) + GROUP_SIDE - 1) / GROUP_SIDE, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                        GL_FRAMEBUFFER_BARRIER_BIT);
        return;
    }
    target.clear(nothing);
    glBindVertexArray(mVertexArray.get());
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT); // back faces: every pixel whose ray meets the box, once, eye inside or not
    glFrontFace(m.mirrored ? GL_CW : GL_CCW);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    if (!abandoned) {
        glDrawArrays(GL_TRIANGLES, 0, 36);
        return;
    }
    // Band after band, each finished before the question: the whole frame is one draw otherwise, which
    // nothing can stop. (A GPU's compute walk above draws a frame in a few ms and is not banded.)
    const int rows = walkBandRows(height);
    glEnable(GL_SCISSOR_TEST);
    for (int y = 0; y < height; y += rows) {
        if (y > 0) glFinish();
        if (abandoned()) {
            glDisable(GL_SCISSOR_TEST);
            glDisable(GL_CULL_FACE); // as VotRenderer leaves it after a finished frame
            throw FrameAbandoned();
        }
        glScissor(0, y, width, std::min(rows, height - y));
        glDrawArrays(GL_TRIANGLES, 0, 36);
    }
    glDisable(GL_SCISSOR_TEST);
}

} // namespace vots::render
