// GlDisplayPass, the display pass as a GL object: R32F texture -> window/level + colour map -> RGBA8.
#pragma once

#include "GlObjects.h"

#include "vots/render/DisplaySettings.h"
#include "vots/render/Image.h"

#include <array>

namespace vots::render {

class GlDisplayPass {
public:
    GlDisplayPass();
    /// Maps the float texture (width x height) and reads RGBA8 back, top row first.
    RgbaImage apply(GLuint floatTexture, int width, int height, const DisplaySettings& settings);

private:
    GlProgram mProgram;
    GlVertexArray mVertexArray;
    std::array<GlTexture, 4> mColormaps; // one 256x1 RGBA8 texture per Colormap
    GlTexture mTarget;
    GlFramebuffer mFramebuffer;
    int mWidth = 0;
    int mHeight = 0;
};

/// Throws RenderError unless `image` has a valid size and width x height pixels.
void checkFloatImage(const FloatImage& image);
/// Writes `image` (top row first) into an R32F texture of its size.
void writeFloatImage(GLuint texture, const FloatImage& image);

} // namespace vots::render
