// GL object creation/deletion and shader program building with readable errors.
#include "GlObjects.h"

#include "vots/fit/Error.h"

#include <vector>

namespace vots::render {

void deleteBuffer(GLuint name) {
    glDeleteBuffers(1, &name);
}
void deleteTexture(GLuint name) {
    glDeleteTextures(1, &name);
}
void deleteFramebuffer(GLuint name) {
    glDeleteFramebuffers(1, &name);
}
void deleteVertexArray(GLuint name) {
    glDeleteVertexArrays(1, &name);
}
void deleteProgram(GLuint name) {
    glDeleteProgram(name);
}

GlBuffer createBuffer() {
    GLuint name = 0;
    glCreateBuffers(1, &name);
    return GlBuffer(name);
}
GlTexture createTexture(GLenum target) {
    GLuint name = 0;
    glCreateTextures(target, 1, &name);
    return GlTexture(name);
}
GlFramebuffer createFramebuffer() {
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    return GlFramebuffer(name);
}
GlVertexArray createVertexArray() {
    GLuint name = 0;
    glCreateVertexArrays(1, &name);
    return GlVertexArray(name);
}

namespace {
GLuint compile(GLenum stage, const char* source, const char* label) {
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw fit::GraphicsError(std::string("shader ") + label +
                                 (stage == GL_VERTEX_SHADER    ? " (vertex)"
                                  : stage == GL_COMPUTE_SHADER ? " (compute)"
                                                               : " (fragment)") +
                                 " does not compile: " + log.data());
    }
    return shader;
}

// Links the compiled shaders (and deletes them); throws with the info log on failure.
GlProgram link(const std::vector<GLuint>& shaders, const char* label) {
    GlProgram program(glCreateProgram());
    for (GLuint shader : shaders)
        glAttachShader(program.get(), shader);
    glLinkProgram(program.get());
    for (GLuint shader : shaders)
        glDeleteShader(shader);
    GLint ok = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
        glGetProgramInfoLog(program.get(), length, nullptr, log.data());
        throw fit::GraphicsError(std::string("program ") + label + " does not link: " + log.data());
    }
    return program;
}
} // namespace

GlProgram buildProgram(const char* vertexSource, const char* fragmentSource, const char* label) {
    const GLuint vs = compile(GL_VERTEX_SHADER, vertexSource, label);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, fragmentSource, label);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    return link({vs, fs}, label);
}

GlProgram buildComputeProgram(const char* computeSource, const char* label) {
    return link({compile(GL_COMPUTE_SHADER, computeSource, label)}, label);
}

void setMatrixUniform(GLuint program, const char* name, const std::array<double, 16>& matrix) {
    float m[16];
    for (int i = 0; i < 16; ++i)
        m[i] = static_cast<float>(matrix[static_cast<std::size_t>(i)]);
    glProgramUniformMatrix4fv(program, glGetUniformLocation(program, name), 1, GL_FALSE, m);
}

void checkGl(const char* step) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw fit::GraphicsError(std::string("OpenGL error ") + std::to_string(error) + " in " + step);
}

} // namespace vots::render
