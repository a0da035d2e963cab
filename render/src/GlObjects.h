// Small RAII owners for GL names and a program builder; private to the renderer.
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <string>
#include <utility>

namespace vots::render {

/// Owns one GL object name; Deleter is a function that deletes it.
template <void (*Deleter)(GLuint)> class GlName {
public:
    GlName() = default;
    explicit GlName(GLuint name) : mName(name) {}
    ~GlName() { reset(); }
    GlName(GlName&& o) noexcept : mName(std::exchange(o.mName, 0)) {}
    GlName& operator=(GlName&& o) noexcept {
        if (this != &o) {
            reset();
            mName = std::exchange(o.mName, 0);
        }
        return *this;
    }
    GLuint get() const { return mName; }
    void reset() {
        if (mName) Deleter(mName);
        mName = 0;
    }

private:
    GLuint mName = 0;
};

void deleteBuffer(GLuint name);
void deleteTexture(GLuint name);
void deleteFramebuffer(GLuint name);
void deleteVertexArray(GLuint name);
void deleteProgram(GLuint name);

using GlBuffer = GlName<deleteBuffer>;
using GlTexture = GlName<deleteTexture>;
using GlFramebuffer = GlName<deleteFramebuffer>;
using GlVertexArray = GlName<deleteVertexArray>;
using GlProgram = GlName<deleteProgram>;

GlBuffer createBuffer();
GlTexture createTexture(GLenum target);
GlFramebuffer createFramebuffer();
GlVertexArray createVertexArray();

/// Compiles and links; throws fit::GraphicsError with the info log (and which shader) on failure.
GlProgram buildProgram(const char* vertexSource, const char* fragmentSource, const char* label);
/// The same for a compute shader alone.
GlProgram buildComputeProgram(const char* computeSource, const char* label);

/// Uploads a column-major double matrix as a float mat4 uniform.
void setMatrixUniform(GLuint program, const char* name, const std::array<double, 16>& matrix);

/// Throws fit::GraphicsError when glGetError reports something (names the step).
void checkGl(const char* step);

} // namespace vots::render
