// Vot MIP / density: a per-pixel walk through a cell -> Vot grid, or instanced boxes into R32F with
// MAX/MIN blending in batches with CPU culling.
#include "vots/render/VotRenderer.h"

#include "BrickAhead.h"
#include "DisplayPass.h"
#include "FloatTarget.h"
#include "GlObjects.h"
#include "MaxPyramid.h"
#include "ParallelChunks.h"
#include "Shaders.h"
#include "SkipBoxes.h"
#include "VotBounds.h"
#include "VotOrder.h"
#include "VotWalkGrid.h"
#include "WalkRecord.h"

#include "vots/fit/Error.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/EglContext.h"
#include "vots/render/Error.h"
#include "vots/render/GpuLayout.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <thread>

namespace vots::render {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr std::size_t FIRST_BATCH = 1024; // Vots drawn before the first culling readback
constexpr std::size_t BATCH_GROWTH = 4;   // each later batch considers 4x as many Vots
constexpr int WALK_BRICK_SHIFT = 4;       // Walk: bricks of 16^3 cells (bench/RESULTS.md compares 8, 16, 32)
constexpr float WALK_BOX_SLACK = 1e-3f;   // Walk: the grid box drawn is grown like Raster's (BOX_SLACK)

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

// One RGBA32UI walk texel: box corners in 16 bits each, and the bound's bits.
void packBox(std::uint32_t* texel, const std::array<int, 3>& lo, const std::array<int, 3>& hi, float bound) {
    packBoxCorners(texel, lo, hi);
    std::memcpy(&texel[3], &bound, sizeof(float));
}

// The walk's box table: per palette entry, the box boxOf(block) of the block it names, Vots first, and
// that block's bound (-inf for an empty block). Entries naming no block stay zero.
template <class BoxOf>
std::vector<std::uint32_t> boxTable(const std::vector<std::uint32_t>& palette,
                                    const std::vector<GpuVot>& vots, std::size_t blockCount, BoxOf boxOf) {
    std::vector<std::uint32_t> texels(4 * palette.size(), 0);
    for (std::size_t i = 0; i < palette.size(); ++i) {
        const std::uint32_t block = palette[i];
        if (block >= blockCount) continue;
        const CellBlock& box = boxOf(block);
        packBox(&texels[4 * i], box.lo, box.hi, block < vots.size() ? vots[block].upperBound : -INFINITY);
    }
    return texels;
}

} // namespace

struct VotRenderer::Impl {
    GlProgram mipProgram = buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_MIP_FRAG, "vot_mip");
    GlProgram densityProgram = buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_DENSITY_FRAG, "vot_density");
    WalkShader walkShader = defaultWalkShader();
    // Fragment and compute, built when first needed; the constructor builds the one frames use, so
    // that a shader this driver refuses shows at once.
    std::array<GlProgram, 2> walkPrograms;
    // Walk strategy (vot_walk.frag): buffer textures over their own buffers.
    GlBuffer cellLocalBuffer, brickMaxBuffer, votBoxBuffer, walkRecordBuffer;
    GlTexture cellLocal; // R16UI per cell, brick by brick: index into the brick's palette
    GlTexture brickMax;  // RGBA32F per brick, x fastest: its bound, the bound ahead for this frame, and
                         // the bits of its first palette index
    std::vector<float> walkBrickMax;             // per brick: max upperBound of the Vots touching it
    std::vector<std::uint32_t> walkPaletteStart; // per brick: its first palette index
    GlTexture walkRecord; // RGBA32UI, WALK_RECORD_TEXELS per palette entry (WalkRecord.h): the record of
                          // the Vot it names, zeros for an empty block
    GlTexture votBox;     // RGBA32UI per palette entry: the packed box to step over and the bound of the
                          // block the entry names (each brick has its own copies of its blocks' boxes)
    std::vector<std::uint32_t> walkPalette; // the palette's block ids, to rewrite votBox with skip boxes
    std::array<int, 3> walkCells{0, 0, 0};
    std::array<int, 3> walkBricks{0, 0, 0};
    bool walkable = false;
    // Skip boxes (SkipBoxes.h) are grown on other threads once a Vot-Space's first frame is drawn, so
    // they never delay it, and replace the boxes in votBox at the next frame: the same images, fewer
    // walk steps. A growth owns its input, so an upload cancels the last one without waiting for it.
    struct WalkGrid {
        VotWalkGrid grid;
        PalettedCells cells;
    };
    struct SkipGrowth {
        SkipGrowthInput input;
        std::atomic<bool> cancel{false};
    };
    std::shared_ptr<SkipGrowth> skipGrowth; // this Vot-Space's, until its boxes are in votBox
    std::future<std::vector<CellBlock>> skipTask;
    std::vector<std::future<std::vector<CellBlock>>> cancelledSkipTasks; // ending on their own
    GlVertexArray vertexArray = createVertexArray();
    GlBuffer votBuffer; // the records of `vots`, made by the first frame that draws Raster or density
    GlBuffer indexBuffer;
    GlTexture votData = createTexture(GL_TEXTURE_BUFFER); // RGBA32F view of the bound chunk (uVotData)
    FloatTarget target;
    GlTexture prevMax; // copy of the max image after the last batch, same size as target
    int prevMaxWidth = 0, prevMaxHeight = 0;
    DisplayPass display;

    bool hasData = false;
    SceneBounds bounds;
    std::vector<GpuVot> vots; // in space order when walkable, else by descending upperBound
    std::vector<std::uint32_t> visible;
    std::size_t chunkRecords = 1; // Vots per SSBO binding (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)
    std::array<float, 2> valueRange{0.f, 0.f};
    std::array<float, 2> densityRange{0.f, 1.f};
    bool culling = true;
    Strategy strategy = Strategy::Walk;
    std::function<void()> backgroundThreadStart;
    FrameStats stats;

    Strategy mipStrategy() const {
        return strategy == Strategy::Walk && walkable ? Strategy::Walk : Strategy::Raster;
    }

    Impl() { useWalkShader(defaultWalkShader()); }

    // Builds the walk program now, so that a shader this driver refuses shows at once; the fragment
    // walk is the one every driver has run, so a compute walk that does not build falls back to it.
    void useWalkShader(WalkShader shader) {
        if (shader == WalkShader::Compute) {
            try {
                walkProgram(true);
                walkShader = shader;
                return;
            } catch (const RenderError& e) {
                std::cerr << "vots: warning: the compute walk does not build here, using the fragment walk: "
                          << e.what() << "\n";
            }
        }
        walkProgram(false);
        walkShader = WalkShader::Fragment;
    }

    // The compute walk spreads over all of a GPU's multiprocessors; a CPU rasteriser runs the
    // fragment walk faster (bench/RESULTS.md, "GPU").
    static WalkShader defaultWalkShader() {
        const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        return renderer && EglContext::isSoftwareRenderer(renderer) ? WalkShader::Fragment
                                                                    : WalkShader::Compute;
    }

    GLuint walkProgram(bool compute) {
        GlProgram& program = walkPrograms[compute ? 1 : 0];
        if (!program.get())
            program = compute ? buildComputeProgram(shaders::VOT_WALK_COMP, "vot_walk_compute")
                              : buildProgram(shaders::WALK_BOX_VERT, shaders::VOT_WALK_FRAG, "vot_walk");
        return program.get();
    }

    ~Impl() {
        if (skipGrowth) skipGrowth->cancel = true;
        for (auto& task : cancelledSkipTasks)
            task.wait();
    }

    // Before a new upload: the running growth is told to stop and left to end by itself.
    void cancelSkipGrowth() {
        if (skipTask.valid()) {
            skipGrowth->cancel = true;
            cancelledSkipTasks.push_back(std::move(skipTask));
        }
        skipGrowth.reset();
        std::erase_if(cancelledSkipTasks, [](const std::future<std::vector<CellBlock>>& task) {
            return task.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
        });
    }

    void startSkipGrowth() {
        if (!skipGrowth || skipTask.valid()) return;
        skipTask = std::async(std::launch::async, [growth = skipGrowth, onStart = backgroundThreadStart] {
            // The caller's priority policy; the growth's worker threads inherit what it sets.
            if (onStart) onStart();
            return growSkipBoxes(growth->input, growth->cancel);
        });
    }

    // Puts finished skip boxes into votBox; with `wait`, waits for them first.
    void applySkipBoxes(bool wait) {
        if (!skipTask.valid()) return;
        if (!wait && skipTask.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
        const std::size_t emptyCount = skipGrowth->input.emptyBlocks.size();
        std::vector<CellBlock> grown;
        try {
            grown = skipTask.get();
        } catch (const std::exception&) {
            // Out of memory, say: the Vots' own boxes stay, which are exact too, only slower.
        }
        skipTask = {};
        skipGrowth.reset();
        if (grown.size() != vots.size() + emptyCount) return;
        const std::vector<std::uint32_t> texels =
            boxTable(walkPalette, vots, grown.size(),
                     [&](std::uint32_t block) -> const CellBlock& { return grown[block]; });
        glNamedBufferSubData(votBoxBuffer.get(), 0,
                             static_cast<GLsizeiptr>(texels.size() * sizeof(std::uint32_t)), texels.data());
        checkGl("VotRenderer skip boxes");
    }

    void ensureVotBuffer() {
        if (votBuffer.get()) return;
        votBuffer = createBuffer();
        glNamedBufferStorage(votBuffer.get(),
                             static_cast<GLsizeiptr>(std::max<std::size_t>(vots.size(), 1) * sizeof(GpuVot)),
                             vots.empty() ? nullptr : vots.data(), 0);
        checkGl("VotRenderer records upload");
    }

    void bindChunk(std::size_t chunk) {
        const std::size_t first = chunk * chunkRecords;
        // The buffer holds at least one record, so an empty space still binds a valid range.
        const std::size_t count = std::max<std::size_t>(std::min(chunkRecords, vots.size() - first), 1);
        const auto offset = static_cast<GLintptr>(first * sizeof(GpuVot));
        const auto bytes = static_cast<GLsizeiptr>(count * sizeof(GpuVot));
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, VOT_BUFFER_BINDING, votBuffer.get(), offset, bytes);
        glTextureBufferRange(votData.get(), GL_RGBA32F, votBuffer.get(), offset, bytes);
        glBindTextureUnit(VOT_TEXTURE_UNIT, votData.get());
    }

    void setCommonState(GLuint program, const CameraMatrices& m, int width, int height) {
        glUseProgram(program);
        if (program == mipProgram.get())
            glProgramUniform1i(program, glGetUniformLocation(program, "uVotData"), VOT_TEXTURE_UNIT);
        setMatrixUniform(program, "uIndexToClip", m.indexToClip);
        setMatrixUniform(program, "uClipToIndex", m.clipToIndex);
        glProgramUniform2f(program, glGetUniformLocation(program, "uViewport"), float(width), float(height));
        glBindVertexArray(vertexArray.get());
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT); // back faces only: one fragment per box and pixel, also from inside a box
        glFrontFace(GL_CCW);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, INDEX_BUFFER_BINDING, indexBuffer.get());
    }

    void drawRange(GLuint program, std::size_t first, std::size_t count, bool useList) {
        glProgramUniform1ui(program, glGetUniformLocation(program, "uFirst"), static_cast<GLuint>(first));
        glProgramUniform1i(program, glGetUniformLocation(program, "uUseList"), useList ? 1 : 0);
        glDrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(count));
        ++stats.batches;
    }

    // Every Vot, chunk by chunk, no culling.
    void drawAll(GLuint program) {
        for (std::size_t chunk = 0; chunk * chunkRecords < vots.size(); ++chunk) {
            bindChunk(chunk);
            drawRange(program, 0, std::min(chunkRecords, vots.size() - chunk * chunkRecords), false);
        }
        stats.votsDrawn = vots.size();
    }

    void ensurePrevMax(int width, int height) {
        if (prevMax.get() && prevMaxWidth == width && prevMaxHeight == height) return;
        prevMax = createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(prevMax.get(), 1, GL_R32F, width, height);
        glTextureParameteri(prevMax.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(prevMax.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        prevMaxWidth = width;
        prevMaxHeight = height;
    }

    // Batches in record order (descending bound unless the walk is the MIP strategy); between batches the max
    // image is read back, Vots that cannot raise any pixel under their box are skipped, and the rest stop
    // early per fragment.
    void drawCulled(const CameraMatrices& m, int width, int height) {
        const GLuint program = mipProgram.get();
        ensurePrevMax(width, height);
        const float minusInf = -INFINITY;
        glClearTexImage(prevMax.get(), 0, GL_RED, GL_FLOAT, &minusInf);
        glBindTextureUnit(0, prevMax.get());
        glProgramUniform1i(program, glGetUniformLocation(program, "uPrevMax"), 0);
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
            // A batch stays inside one SSBO chunk; indices in `visible` are relative to the chunk.
            const std::size_t chunk = next / chunkRecords;
            const std::size_t chunkFirst = chunk * chunkRecords;
            const std::size_t end = std::min({next + batch, vots.size(), chunkFirst + chunkRecords});
            std::size_t count = 0;
            for (std::size_t i = next; i < end; ++i) {
                int rect[4];
                if (!projectBox(matrix, vots[i], width, height, rect)) continue;
                if (havePyramid && vots[i].upperBound <= pyramid.minOver(rect[0], rect[1], rect[2], rect[3]))
                    continue;
                visible[count++] = static_cast<std::uint32_t>(i - chunkFirst);
            }
            if (count > 0) {
                glNamedBufferSubData(indexBuffer.get(), 0,
                                     static_cast<GLsizeiptr>(count * sizeof(std::uint32_t)), visible.data());
                bindChunk(chunk);
                drawRange(program, 0, count, true);
                stats.votsDrawn += count;
            }
            next = end;
            batch *= BATCH_GROWTH;
            if (next < vots.size() && count > 0) {
                glGetTextureImage(target.texture(), 0, GL_RED, GL_FLOAT,
                                  static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
                pyramid.build(pixels.data(), width, height);
                havePyramid = true;
                glCopyImageSubData(target.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, prevMax.get(), GL_TEXTURE_2D,
                                   0, 0, 0, 0, width, height, 1);
            }
        }
    }

    // Each pixel walks its ray (vot_walk.glsl): one compute invocation per pixel, or one pass over the
    // back faces of the grid box.
    void drawWalk(const CameraMatrices& m, int width, int height) {
        applySkipBoxes(false);
        const bool compute = walkShader == WalkShader::Compute;
        const GLuint p = walkProgram(compute);
        glUseProgram(p);
        setMatrixUniform(p, "uIndexToClip", m.indexToClip);
        setMatrixUniform(p, "uClipToIndex", m.clipToIndex);
        glProgramUniform2f(p, glGetUniformLocation(p, "uViewport"), float(width), float(height));
        glProgramUniform3f(p, glGetUniformLocation(p, "uBoxLo"), -WALK_BOX_SLACK, -WALK_BOX_SLACK,
                           -WALK_BOX_SLACK);
        glProgramUniform3f(p, glGetUniformLocation(p, "uBoxHi"), float(walkCells[0]) + WALK_BOX_SLACK,
                           float(walkCells[1]) + WALK_BOX_SLACK, float(walkCells[2]) + WALK_BOX_SLACK);
        glProgramUniform3i(p, glGetUniformLocation(p, "uCells"), walkCells[0], walkCells[1], walkCells[2]);
        glProgramUniform3i(p, glGetUniformLocation(p, "uBricks"), walkBricks[0], walkBricks[1],
                           walkBricks[2]);
        glProgramUniform1i(p, glGetUniformLocation(p, "uBrickShift"), WALK_BRICK_SHIFT);
        glProgramUniform1i(p, glGetUniformLocation(p, "uCull"), culling ? 1 : 0);
        // The bounds ahead depend on the view: a few thousand bricks, recomputed per frame.
        const std::vector<float> ahead = brickMaximaAhead({walkCells, walkBricks, WALK_BRICK_SHIFT},
                                                          walkBrickMax, rayFamilyOf(m.clipToIndex));
        std::vector<float> brickBounds(4 * ahead.size()); // (bound, bound ahead, palette start, 0) per brick
        for (std::size_t i = 0; i < ahead.size(); ++i) {
            brickBounds[4 * i] = walkBrickMax[i];
            brickBounds[4 * i + 1] = ahead[i];
            std::memcpy(&brickBounds[4 * i + 2], &walkPaletteStart[i], sizeof(float));
        }
        glNamedBufferSubData(brickMaxBuffer.get(), 0,
                             static_cast<GLsizeiptr>(brickBounds.size() * sizeof(float)), brickBounds.data());
        glProgramUniform1i(p, glGetUniformLocation(p, "uCellLocal"), 0);
        glProgramUniform1i(p, glGetUniformLocation(p, "uBrickMax"), 1);
        glProgramUniform1i(p, glGetUniformLocation(p, "uVotBox"), 2);
        glProgramUniform1i(p, glGetUniformLocation(p, "uWalkRecord"), 3);
        glBindTextureUnit(0, cellLocal.get());
        glBindTextureUnit(1, brickMax.get());
        glBindTextureUnit(2, votBox.get());
        glBindTextureUnit(3, walkRecord.get());
        stats.batches = 1;
        if (compute) {
            constexpr GLuint GROUP_SIDE = 8; // local_size in vot_walk.comp
            glBindImageTexture(0, target.texture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
            glDispatchCompute((static_cast<GLuint>(width) + GROUP_SIDE - 1) / GROUP_SIDE,
                              (static_cast<GLuint>(height) + GROUP_SIDE - 1) / GROUP_SIDE, 1);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                            GL_FRAMEBUFFER_BARRIER_BIT);
            stats.votsDrawn = 0;
            return;
        }
        target.clear(-INFINITY);
        glBindVertexArray(vertexArray.get());
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT); // back faces: every pixel whose ray meets the box, once, eye inside or not
        glFrontFace(GL_CCW);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDrawArrays(GL_TRIANGLES, 0, 36);
        stats.votsDrawn = 0;
    }

    // The Walk grid for the records in `vots`, or nullopt when the walk cannot draw them, so that MIP
    // frames use Raster: boxes that overlap (the walk sees one Vot per cell), or more than the GL
    // limits hold.
    std::optional<WalkGrid> walkGridFor(const std::array<int, 3>& dims) const {
        for (int a = 0; a < 3; ++a)
            if (dims[a] - 1 > 0xffff) return std::nullopt; // box corners are packed in 16 bits
        std::optional<VotWalkGrid> grid = buildVotWalkGrid(vots, dims, WALK_BRICK_SHIFT, nullptr);
        if (!grid) return std::nullopt;
        PalettedCells cells = palettedCells(*grid);
        GLint maxTexels = 0;
        glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
        const std::size_t cellCount = grid->brickMax.size() << (3 * grid->brickShift);
        if (std::max(cellCount, WALK_RECORD_TEXELS * cells.palette.size()) >=
            static_cast<std::size_t>(maxTexels))
            return std::nullopt;
        return WalkGrid{std::move(*grid), std::move(cells)};
    }

    // Uploads the Walk grid (walkable true), or drops the last one when there is none. votRecords holds
    // WALK_RECORD_WORDS words per Vot, in the order of `vots`.
    void uploadWalkGrid(std::optional<WalkGrid>&& walk, const std::uint32_t* votRecords) {
        walkable = false;
        for (GlTexture* t : {&cellLocal, &brickMax, &votBox, &walkRecord})
            t->reset();
        for (GlBuffer* b : {&cellLocalBuffer, &brickMaxBuffer, &votBoxBuffer, &walkRecordBuffer})
            b->reset();
        if (!walk) return;
        VotWalkGrid* grid = &walk->grid;
        PalettedCells& cells = walk->cells;
        const std::size_t blocks = vots.size() + grid->emptyBlocks.size();

        // What the skip-box growth will read; the Vots' own boxes are also the first box table.
        skipGrowth = std::make_shared<SkipGrowth>();
        SkipGrowthInput& in = skipGrowth->input;
        in.cells = grid->cells;
        in.votBoxes.resize(vots.size());
        in.votBounds.resize(vots.size());
        for (std::size_t i = 0; i < vots.size(); ++i) {
            in.votBoxes[i] = cellBlockOf(vots[i]);
            in.votBounds[i] = vots[i].upperBound;
        }

        // One RGBA32UI texel per palette entry, the box and bound of the block it names (bound -inf for
        // an empty block): a step reads it straight after the cell, and a brick's entries share cache
        // lines, where one table by block index cost another dependent read per step.
        const std::vector<std::uint32_t> boxes =
            boxTable(cells.palette, vots, blocks, [&](std::uint32_t block) -> const CellBlock& {
                return block < vots.size() ? in.votBoxes[block] : grid->emptyBlocks[block - vots.size()];
            });

        auto bufferTexture = [](GlBuffer& buffer, GlTexture& texture, GLenum format, const void* data,
                                std::size_t bytes) {
            buffer = createBuffer();
            glNamedBufferStorage(buffer.get(), static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_STORAGE_BIT);
            texture = createTexture(GL_TEXTURE_BUFFER);
            glTextureBuffer(texture.get(), format, buffer.get());
        };
        bufferTexture(cellLocalBuffer, cellLocal, GL_R16UI, cells.local.data(),
                      cells.local.size() * sizeof(std::uint16_t));
        walkBrickMax = grid->brickMax;
        walkPaletteStart = std::move(cells.paletteStart);
        walkPalette = std::move(cells.palette);
        // Written by every walk frame before it draws (drawWalk): the bounds ahead depend on the view.
        bufferTexture(brickMaxBuffer, brickMax, GL_RGBA32F, nullptr, 4 * walkBrickMax.size() * sizeof(float));
        bufferTexture(votBoxBuffer, votBox, GL_RGBA32UI, boxes.data(), boxes.size() * sizeof(std::uint32_t));
        // Walk records by palette entry, like the box table: a step that evaluates reads the record
        // straight after the box, with no lookup of the Vot's index between them. Only 4 % of the CT's
        // Vots have entries in two bricks; entries of empty blocks stay zero (10 % of the entries).
        // Written straight into the mapped buffer: a copy through memory of our own cost as much again
        // (17.6 MB at 237 k Vots). At least one record, so that an empty space binds a valid buffer.
        const std::size_t recordBytes = WALK_RECORD_WORDS * sizeof(std::uint32_t);
        const std::size_t entries = std::max<std::size_t>(walkPalette.size(), 1);
        walkRecordBuffer = createBuffer();
        glNamedBufferStorage(walkRecordBuffer.get(), static_cast<GLsizeiptr>(entries * recordBytes), nullptr,
                             GL_MAP_WRITE_BIT);
        auto* mapped = static_cast<std::uint32_t*>(
            glMapNamedBufferRange(walkRecordBuffer.get(), 0, static_cast<GLsizeiptr>(entries * recordBytes),
                                  GL_MAP_WRITE_BIT | GL_MAP_INVALIDATE_BUFFER_BIT));
        if (!mapped) throw RenderError("VotRenderer: could not map the walk records for writing");
        parallelChunks(entries, [&](std::size_t first, std::size_t last) {
            for (std::size_t i = first; i < last; ++i) {
                std::uint32_t* out = mapped + i * WALK_RECORD_WORDS;
                if (i < walkPalette.size() && walkPalette[i] < vots.size())
                    std::copy_n(&votRecords[walkPalette[i] * WALK_RECORD_WORDS], WALK_RECORD_WORDS, out);
                else
                    std::fill_n(out, WALK_RECORD_WORDS, 0u);
            }
        });
        glUnmapNamedBuffer(walkRecordBuffer.get());
        walkRecord = createTexture(GL_TEXTURE_BUFFER);
        glTextureBuffer(walkRecord.get(), GL_RGBA32UI, walkRecordBuffer.get());
        in.cellVot = std::move(grid->cellVot);
        in.emptyBlocks = std::move(grid->emptyBlocks);
        checkGl("VotRenderer walk grid upload");
        walkCells = grid->cells;
        walkBricks = grid->bricks;
        walkable = true;
    }

    void draw(const Camera& camera, int width, int height, RenderMode mode) {
        if (mode == RenderMode::Reference)
            throw fit::InputError(
                "VotRenderer draws mip or density; reference needs the volume (GridRenderer)");
        if (!hasData) throw RenderError("VotRenderer: render() before upload()");
        const CameraMatrices m = computeCameraMatrices(camera, bounds, width, height);
        const auto t0 = Clock::now();
        stats = FrameStats{};
        stats.votsTotal = vots.size();
        target.bind(width, height);
        if (mode == RenderMode::Mip && mipStrategy() == Strategy::Walk) {
            drawWalk(m, width, height); // writes every pixel
            glDisable(GL_CULL_FACE);
            glFinish();
            stats.gpuMs = msSince(t0);
            checkGl("VotRenderer walk");
            startSkipGrowth();
            return;
        }
        const GLuint program = mode == RenderMode::Mip ? mipProgram.get() : densityProgram.get();
        ensureVotBuffer();
        setCommonState(program, m, width, height);
        if (mode == RenderMode::Mip) {
            target.clear(-INFINITY);
            glBlendEquation(GL_MAX); // exact for R32F (EGL_NOTES); order-independent, no sorting needed
            if (culling && vots.size() > FIRST_BATCH) {
                drawCulled(m, width, height);
            } else {
                glProgramUniform1i(program, glGetUniformLocation(program, "uUsePrevMax"), 0);
                drawAll(program);
            }
        } else {
            target.clear(INFINITY);
            glBlendEquation(GL_MIN);
            drawAll(program);
        }
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glFinish();
        stats.gpuMs = msSince(t0);
        checkGl("VotRenderer draw");
    }
};

VotRenderer::VotRenderer() : mImpl(std::make_unique<Impl>()) {}
VotRenderer::~VotRenderer() = default;

void VotRenderer::upload(const fit::VotSpace& space) {
    Impl& d = *mImpl;
    d.cancelSkipGrowth();
    std::vector<VotBounds> bounds(space.vots.size());
    // Records go straight to their place in space order (the walk's order), not through a copy: 30 MB
    // at 237 k Vots, and a refit waits for the upload.
    const std::vector<std::size_t> order = spatialOrder(space.vots);
    std::vector<std::size_t> place(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        place[order[i]] = i;
    d.vots.resize(space.vots.size());
    // Left uninitialised: every word is written below (15 MB at 237 k Vots).
    const std::unique_ptr<std::uint32_t[]> walkRecords(
        new std::uint32_t[space.vots.size() * WALK_RECORD_WORDS]);
    {
        // Bounds and records dominate an upload; each Vot is independent, so split evenly.
        parallelChunks(space.vots.size(), [&](std::size_t first, std::size_t last) {
            for (std::size_t i = first; i < last; ++i) {
                bounds[i] = computeVotBounds(space.vots[i]);
                const WalkRecord walk = makeWalkRecord(space.vots[i]);
                std::copy(walk.words.begin(), walk.words.end(), &walkRecords[place[i] * WALK_RECORD_WORDS]);
                // The walk evaluates its record's polynomial, which strays from the Vot's by up to
                // maxError: every bound covers both, so culling by it never changes either image.
                bounds[i].floatSlack += walk.maxError;
                d.vots[place[i]] = makeGpuVot(space.vots[i], bounds[i]);
            }
        });
    }
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
    if (chunk == 0) throw RenderError("GL shader storage blocks are too small for one Vot");
    d.chunkRecords = chunk;

    std::optional<Impl::WalkGrid> grid = d.walkGridFor(space.dims);
    if (!grid) {
        // Bound order when Raster draws the MIP instead.
        const std::vector<std::size_t> byBound = boundOrder(bounds);
        std::vector<GpuVot> inSpaceOrder = std::move(d.vots);
        d.vots.resize(byBound.size());
        for (std::size_t i = 0; i < byBound.size(); ++i)
            d.vots[i] = inSpaceOrder[place[byBound[i]]];
    }

    float lo = INFINITY, hi = -INFINITY, maxLogSize = 0.f;
    for (std::size_t i = 0; i < bounds.size(); ++i) {
        lo = std::min(lo, static_cast<float>(bounds[i].lower));
        hi = std::max(hi, static_cast<float>(bounds[i].upper));
        maxLogSize = std::max(maxLogSize, d.vots[i].logSize);
    }
    if (d.vots.empty()) lo = hi = 0.f;
    d.valueRange = {lo, hi};
    d.densityRange = {0.f, std::max(maxLogSize, 1.f)};

    d.votBuffer.reset(); // the walk reads its own records: most spaces never need these 30 MB in GL
    d.visible.assign(std::max<std::size_t>(std::min(d.vots.size(), chunk), 1), 0);
    d.indexBuffer = createBuffer();
    glNamedBufferStorage(d.indexBuffer.get(),
                         static_cast<GLsizeiptr>(d.visible.size() * sizeof(std::uint32_t)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    checkGl("VotRenderer upload");
    d.uploadWalkGrid(std::move(grid), walkRecords.get());
    d.bounds = sceneBounds(space);
    d.hasData = true;
}

bool VotRenderer::hasData() const {
    return mImpl->hasData;
}
const SceneBounds& VotRenderer::bounds() const {
    return mImpl->bounds;
}
std::array<float, 2> VotRenderer::valueRange() const {
    return mImpl->valueRange;
}
std::array<float, 2> VotRenderer::densityRange() const {
    return mImpl->densityRange;
}
void VotRenderer::setCulling(bool enabled) {
    mImpl->culling = enabled;
}
void VotRenderer::setStrategy(Strategy strategy) {
    mImpl->strategy = strategy;
}
VotRenderer::Strategy VotRenderer::strategy() const {
    return mImpl->strategy;
}
VotRenderer::Strategy VotRenderer::mipStrategy() const {
    return mImpl->mipStrategy();
}
std::string_view walkShaderName(VotRenderer::WalkShader shader) {
    return shader == VotRenderer::WalkShader::Compute ? "compute" : "fragment";
}

std::optional<VotRenderer::WalkShader> parseWalkShader(std::string_view name) {
    for (const auto shader : {VotRenderer::WalkShader::Fragment, VotRenderer::WalkShader::Compute})
        if (name == walkShaderName(shader)) return shader;
    return std::nullopt;
}

void VotRenderer::setWalkShader(WalkShader shader) {
    mImpl->useWalkShader(shader);
}
void VotRenderer::setBackgroundThreadStart(std::function<void()> onStart) {
    mImpl->backgroundThreadStart = std::move(onStart);
}
VotRenderer::WalkShader VotRenderer::walkShader() const {
    return mImpl->walkShader;
}

void VotRenderer::finishPendingWork() {
    mImpl->startSkipGrowth();
    mImpl->applySkipBoxes(true);
}
const FrameStats& VotRenderer::lastFrameStats() const {
    return mImpl->stats;
}

FloatImage VotRenderer::render(const Camera& camera, int width, int height, RenderMode mode) {
    mImpl->draw(camera, width, height, mode);
    const auto t0 = Clock::now();
    FloatImage image = mImpl->target.readback();
    mImpl->stats.readbackMs = msSince(t0);
    return image;
}

RgbaImage VotRenderer::renderRgba(const Camera& camera, int width, int height, const DisplaySettings& display,
                                  RenderMode mode) {
    mImpl->draw(camera, width, height, mode);
    const auto t0 = Clock::now();
    RgbaImage image = mImpl->display.apply(mImpl->target.texture(), width, height, display);
    mImpl->stats.readbackMs = msSince(t0);
    return image;
}

} // namespace vots::render
