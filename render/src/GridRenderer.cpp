// Exact grid projection (mip, minip, aip): a fullscreen pass per z chunk walks each ray cell by cell.
#include "vots/render/GridRenderer.h"

#include "FloatTarget.h"
#include "FrameReadout.h"
#include "GlObjects.h"
#include "Shaders.h"
#include "SlabClip.h"

#include "vots/fit/Error.h"
#include "vots/fit/Volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace vots::render {

namespace {

// One 3D texture's share of the z range: it owns the cells with cellZ[0] <= z < cellZ[1] and holds the
// planes cellZ[0] .. cellZ[1], the 8 corners of every cell it owns (read with texelFetch).
struct Chunk {
    GlTexture texture;
    int firstPlane = 0; // the grid z of the texture's plane 0
    int planes = 0;
    std::array<int, 2> cellZ{0, 0};
};

// What each mode's pixels start at, and how the chunks' values combine (one chunk: they are written).
struct ModeBlend {
    int shaderMode; // grid_exact.frag's uMode
    float clearValue;
    GLenum equation;
};
ModeBlend modeBlend(RenderMode mode) {
    switch (mode) {
    case RenderMode::MinIp:
        return {1, INFINITY, GL_MIN};
    // Each chunk writes its part of the integral over the whole ray's length: the parts add to the mean.
    case RenderMode::Aip:
        return {2, 0.f, GL_FUNC_ADD};
    default:
        return {0, -INFINITY, GL_MAX};
    }
}

// A texture of more bytes than this is split too: llvmpipe and drivers fail on huge textures well
// before they run out of memory, and a frame's chunks are drawn one after another anyway.
constexpr std::size_t MAX_CHUNK_BYTES = std::size_t{1} << 30;

// How a volume's samples go into its textures: floats as R32F, 8- and 16-bit samples held in their
// source type (fit::Volume::compact) as integer textures of that type, half or a quarter the memory. The
// shader converts each texel to float, which gives the float-held sample exactly, so the images match.
struct TexelFormat {
    GLenum internalFormat;
    GLenum pixelFormat;
    GLenum pixelType;
    const char* sampler; // grid_exact.frag's VOLUME_SAMPLER
};

template <typename T> TexelFormat texelFormatOf() {
    if constexpr (std::is_same_v<T, std::uint8_t>)
        return {GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, "usampler3D"};
    else if constexpr (std::is_same_v<T, std::int8_t>)
        return {GL_R8I, GL_RED_INTEGER, GL_BYTE, "isampler3D"};
    else if constexpr (std::is_same_v<T, std::uint16_t>)
        return {GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT, "usampler3D"};
    else if constexpr (std::is_same_v<T, std::int16_t>)
        return {GL_R16I, GL_RED_INTEGER, GL_SHORT, "isampler3D"};
    else
        return {GL_R32F, GL_RED, GL_FLOAT, "sampler3D"};
}

/// Calls body(format, const T* samples) with the samples as the volume holds them.
template <typename Body> void visitHeldSamples(const fit::Volume& volume, Body&& body) {
    if (!volume.isCompact()) return body(texelFormatOf<float>(), volume.values.data());
    std::visit(
        [&](const auto& held) {
            using Held = std::decay_t<decltype(held)>;
            if constexpr (!std::is_same_v<Held, std::monostate>)
                body(texelFormatOf<typename Held::value_type>(), held.data());
        },
        volume.compact);
}

/// grid_exact.frag with its sampler type defined on the line after `#version`.
std::string gridShaderFor(const char* sampler) {
    std::string source = shaders::GRID_EXACT_FRAG;
    const std::size_t afterVersion = source.find('\n') + 1;
    source.insert(afterVersion, std::string("#define VOLUME_SAMPLER ") + sampler + "\n");
    return source;
}

} // namespace

struct GridRenderer::Impl {
    std::map<std::string, GlProgram> programs; // by sampler type: floats' at once, so a driver that
                                               // cannot compile it fails here; the others when needed
    GLuint program = programFor(texelFormatOf<float>().sampler); // reads the uploaded textures
    GlVertexArray vertexArray = createVertexArray();
    std::vector<Chunk> chunks;
    int chunkPlaneLimit = 0; // 0: from the GL limit and MAX_CHUNK_BYTES
    FloatTarget target;
    bool hasData = false;
    SceneBounds bounds;
    std::array<float, 2> valueRange{0.f, 0.f};
    std::optional<float> noDataValue; // useNoDataValue's; empty: valueRange[0]
    FrameStats stats;

    GLuint programFor(const std::string& sampler) {
        auto found = programs.find(sampler);
        if (found == programs.end()) {
            const std::string fragment = gridShaderFor(sampler.c_str());
            found =
                programs
                    .emplace(sampler, buildProgram(shaders::FULLSCREEN_VERT, fragment.c_str(), "grid_exact"))
                    .first;
        }
        return found->second.get();
    }

    void draw(const Camera& camera, int width, int height, const RenderOptions& options) {
        if (!hasData) throw fit::GraphicsError("GridRenderer: render() before upload()");
        const CameraMatrices m = computeCameraMatrices(camera, bounds, width, height);
        const auto t0 = FrameClock::now();
        stats = FrameStats{};
        target.bind(width, height);
        const ModeBlend blend = modeBlend(options.mode);
        // A ray that misses the grid (or slab) writes the background in every chunk: -inf for mip and
        // aip (0 + -inf + -inf stays -inf), +inf for minip.
        target.clear(blend.clearValue);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_DEPTH_TEST);
        const GLuint p = program;
        glUseProgram(p);
        setMatrixUniform(p, "uClipToIndex", m.clipToIndex);
        glProgramUniform2f(p, glGetUniformLocation(p, "uViewport"), float(width), float(height));
        glProgramUniform3f(p, glGetUniformLocation(p, "uDims"), float(bounds.dims[0]), float(bounds.dims[1]),
                           float(bounds.dims[2]));
        glProgramUniform1i(p, glGetUniformLocation(p, "uMode"), blend.shaderMode);
        glProgramUniform1f(p, glGetUniformLocation(p, "uNoDataValue"), noDataValue.value_or(valueRange[0]));
        setSlabUniforms(p, options.slab, camera, bounds);
        glProgramUniform1i(p, glGetUniformLocation(p, "uVolume"), 0);
        glBindVertexArray(vertexArray.get());
        if (chunks.size() > 1) {
            glEnable(GL_BLEND);
            glBlendEquation(blend.equation);
            glBlendFunc(GL_ONE, GL_ONE); // only GL_FUNC_ADD uses it
        }
        for (const Chunk& chunk : chunks) {
            glProgramUniform3f(p, glGetUniformLocation(p, "uChunkOrigin"), 0.f, 0.f, float(chunk.firstPlane));
            glProgramUniform2i(p, glGetUniformLocation(p, "uCellZ"), chunk.cellZ[0], chunk.cellZ[1]);
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
    uploadPlanes(volume, 0, volume);
}

void GridRenderer::uploadPlanes(const fit::Volume& volume, int firstPlane, const fit::Volume& whole) {
    Impl& d = *mImpl;
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
    for (int a = 0; a < 3; ++a)
        if (whole.dims[a] < 2 || (a < 2 && whole.dims[a] > maxSide))
            throw fit::InputError("volume side " + std::to_string(whole.dims[a]) + " outside 2.." +
                                  std::to_string(maxSide) + " for the reference renderer");
    if (volume.heldSamples() != volume.sampleCount())
        throw fit::InputError("volume has the wrong number of samples");
    const int lastPlane = firstPlane + volume.dims[2] - 1;
    if (volume.dims[0] != whole.dims[0] || volume.dims[1] != whole.dims[1] || firstPlane < 0 ||
        volume.dims[2] < 1 || lastPlane >= whole.dims[2])
        throw fit::InputError("planes " + std::to_string(firstPlane) + ".." + std::to_string(lastPlane) +
                              " are not planes of the volume's grid");
    const std::size_t planeSamples =
        static_cast<std::size_t>(volume.dims[0]) * static_cast<std::size_t>(volume.dims[1]);
    // Sized as floats whatever the texel: the chunks decide the order of aip's sums, so a volume gives
    // the same image held as floats or in its source type.
    int planeLimit =
        d.chunkPlaneLimit > 0
            ? d.chunkPlaneLimit
            : static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(maxSide),
                                                     MAX_CHUNK_BYTES / (planeSamples * sizeof(float))));
    if (planeLimit < 4)
        throw fit::InputError("volume planes too large for the reference renderer's textures");
    // Chunk k owns the cells z in [k (P - 1), (k + 1) (P - 1)) from the first plane uploaded: P planes,
    // the last shared with the next. One plane alone owns no cell and has no chunk: it draws nothing.
    const int ownedCells = planeLimit - 1;
    std::vector<Chunk> chunks;
    for (int z = firstPlane; z < lastPlane; z += ownedCells) {
        Chunk chunk;
        chunk.firstPlane = z;
        chunk.cellZ = {z, std::min(lastPlane, z + ownedCells)};
        chunk.planes = chunk.cellZ[1] - z + 1;
        chunks.push_back(std::move(chunk));
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1); // rows of 8- and 16-bit samples need not fill 4 bytes
    std::string sampler;
    visitHeldSamples(volume, [&](const TexelFormat& format, const auto* samples) {
        sampler = format.sampler;
        for (Chunk& chunk : chunks) {
            chunk.texture = createTexture(GL_TEXTURE_3D);
            const GLuint t = chunk.texture.get();
            glTextureStorage3D(t, 1, format.internalFormat, volume.dims[0], volume.dims[1], chunk.planes);
            glTextureSubImage3D(t, 0, 0, 0, 0, volume.dims[0], volume.dims[1], chunk.planes,
                                format.pixelFormat, format.pixelType,
                                samples +
                                    static_cast<std::size_t>(chunk.firstPlane - firstPlane) * planeSamples);
            // texelFetch of the corners only; no filtering (integer textures have none anyway).
            glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            checkGl("GridRenderer upload");
        }
    });
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4); // GL's default, which other uploads expect
    d.program = d.programFor(sampler);
    d.chunks = std::move(chunks);
    d.bounds = sceneBounds(whole);
    d.valueRange = volume.valueRange();
    d.noDataValue.reset();
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
void GridRenderer::useNoDataValue(float value) {
    mImpl->noDataValue = value;
}

std::array<float, 2> GridRenderer::valueRange() const {
    return mImpl->valueRange;
}

const FrameStats& GridRenderer::lastFrameStats() const {
    return mImpl->stats;
}

namespace {
void checkGridMode(const RenderOptions& options) {
    if (options.mode == RenderMode::Density)
        throw fit::InputError("the grid renderer draws mip, minip and aip; density needs a Vot-Space");
}
} // namespace

FloatImage GridRenderer::render(const Camera& camera, int width, int height, const RenderOptions& options) {
    checkGridMode(options);
    mImpl->draw(camera, width, height, options);
    return readFloatFrame(mImpl->target, mImpl->stats);
}

} // namespace vots::render
