// An offscreen framebuffer with one R32F colour texture, resized on demand; readback flips to top-first.
#pragma once

#include "GlObjects.h"

#include "vots/render/Image.h"

namespace vots::render {

class FloatTarget {
public:
    /// (Re)allocates when the size changes; binds the framebuffer and sets the viewport.
    void bind(int width, int height);
    /// Clears the colour attachment to one value (e.g. -inf for MAX blending).
    void clear(float value);
    /// Reads the colour attachment back, top row first.
    FloatImage readback() const;
    GLuint texture() const { return mTexture.get(); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }

private:
    GlTexture mTexture;
    GlFramebuffer mFramebuffer;
    int mWidth = 0;
    int mHeight = 0;
};

} // namespace vots::render
