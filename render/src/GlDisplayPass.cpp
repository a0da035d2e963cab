// The display pass (GlDisplayPass) and applyDisplay, the public call of it on any float image.
#include "GlDisplayPass.h"

#include "Shaders.h"

#include "vots/fit/Error.h"
#include "vots/render/DisplayPass.h"

#include <algorithm>

namespace vots::render {

GlDisplayPass::GlDisplayPass()
    : mProgram(buildProgram(shaders::FULLSCREEN_VERT, shaders::DISPLAY_FRAG, "display")),
      mVertexArray(createVertexArray()) {
    for (Colormap map : ALL_COLORMAPS) {
        GlTexture& t = mColormaps[static_cast<std::size_t>(map)];
        t = createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(t.get(), 1, GL_RGBA8, 256, 1);
        glTextureSubImage2D(t.get(), 0, 0, 0, 256, 1, GL_RGBA, GL_UNSIGNED_BYTE, colormapTable(map).data());
    }
}

RgbaImage GlDisplayPass::apply(GLuint floatTexture, int width, int height, const DisplaySettings& settings) {
    checkImageSize(width, height);
    if (!(settings.width > 0.f)) throw fit::GraphicsError("display window width must be > 0");
    if (width != mWidth || height != mHeight || !mFramebuffer.get()) {
        mTarget = createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(mTarget.get(), 1, GL_RGBA8, width, height);
        mFramebuffer = createFramebuffer();
        glNamedFramebufferTexture(mFramebuffer.get(), GL_COLOR_ATTACHMENT0, mTarget.get(), 0);
        if (glCheckNamedFramebufferStatus(mFramebuffer.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw fit::GraphicsError("RGBA8 framebuffer incomplete");
        mWidth = width;
        mHeight = height;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.get());
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(mProgram.get());
    glBindTextureUnit(0, floatTexture);
    glBindTextureUnit(1, mColormaps[static_cast<std::size_t>(settings.colormap)].get());
    glProgramUniform1i(mProgram.get(), glGetUniformLocation(mProgram.get(), "uImage"), 0);
    glProgramUniform1i(mProgram.get(), glGetUniformLocation(mProgram.get(), "uColormap"), 1);
    glProgramUniform1f(mProgram.get(), glGetUniformLocation(mProgram.get(), "uLow"), settings.low());
    glProgramUniform1f(mProgram.get(), glGetUniformLocation(mProgram.get(), "uWidth"), settings.width);
    glBindVertexArray(mVertexArray.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);

    RgbaImage image;
    image.width = width;
    image.height = height;
    image.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                         image.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                         image.pixels.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row));
    checkGl("display pass");
    return image;
}

void checkFloatImage(const FloatImage& image) {
    checkImageSize(image.width, image.height);
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
        throw fit::GraphicsError("float image has the wrong number of pixels");
}

void writeFloatImage(GLuint texture, const FloatImage& image) {
    // Images are top row first; GL textures start at the bottom row.
    std::vector<float> flipped(image.pixels.size());
    const std::size_t row = static_cast<std::size_t>(image.width);
    for (int y = 0; y < image.height; ++y)
        std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row), row,
                    flipped.begin() + static_cast<std::ptrdiff_t>((image.height - 1 - y) * row));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RED, GL_FLOAT, flipped.data());
}

RgbaImage applyDisplay(const FloatImage& image, const DisplaySettings& display) {
    checkFloatImage(image);
    GlTexture texture = createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), 1, GL_R32F, image.width, image.height);
    writeFloatImage(texture.get(), image);
    GlDisplayPass pass;
    return pass.apply(texture.get(), image.width, image.height, display);
}

} // namespace vots::render
