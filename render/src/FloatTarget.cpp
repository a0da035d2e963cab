// R32F render target: allocation, clearing and top-first readback.
#include "FloatTarget.h"

#include "vots/fit/Error.h"

#include <algorithm>

namespace vots::render {

void FloatTarget::bind(int width, int height) {
    checkImageSize(width, height);
    if (width != mWidth || height != mHeight || !mFramebuffer.get()) {
        mTexture = createTexture(GL_TEXTURE_2D);
        glTextureStorage2D(mTexture.get(), 1, GL_R32F, width, height);
        glTextureParameteri(mTexture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(mTexture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        mFramebuffer = createFramebuffer();
        glNamedFramebufferTexture(mFramebuffer.get(), GL_COLOR_ATTACHMENT0, mTexture.get(), 0);
        if (glCheckNamedFramebufferStatus(mFramebuffer.get(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw fit::GraphicsError("R32F framebuffer incomplete");
        mWidth = width;
        mHeight = height;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.get());
    glViewport(0, 0, width, height);
}

void FloatTarget::clear(float value) {
    const float v[4] = {value, value, value, value};
    glClearNamedFramebufferfv(mFramebuffer.get(), GL_COLOR, 0, v);
}

FloatImage FloatTarget::readback() const {
    FloatImage image;
    image.width = mWidth;
    image.height = mHeight;
    image.pixels.resize(static_cast<std::size_t>(mWidth) * static_cast<std::size_t>(mHeight));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(mTexture.get(), 0, GL_RED, GL_FLOAT,
                      static_cast<GLsizei>(image.pixels.size() * sizeof(float)), image.pixels.data());
    // GL rows go bottom-up; images hand out top row first (PNG order).
    const std::size_t row = static_cast<std::size_t>(mWidth);
    for (int y = 0; y < mHeight / 2; ++y)
        std::swap_ranges(image.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                         image.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                         image.pixels.begin() + static_cast<std::ptrdiff_t>((mHeight - 1 - y) * row));
    return image;
}

} // namespace vots::render
