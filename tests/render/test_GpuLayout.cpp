// The C++ GpuVot mirror matches the std430 layout the linked Vot program reports (offsets, strides).
#include "GlObjects.h"
#include "RenderTestSupport.h"
#include "Shaders.h"

#include "vots/render/GpuLayout.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <sstream>

using namespace vots::render;

namespace {
struct Field {
    const char* glslName;
    std::size_t cppOffset;
};
} // namespace

TEST(GpuLayout, MatchesLinkedProgram) {
    vots::test::glContext();
    const GlProgram program = buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_MIP_FRAG, "layout test");
    const Field fields[] = {
        {"vots[0].lo", offsetof(GpuVot, lo)}, {"vots[0].upperBound", offsetof(GpuVot, upperBound)},
        {"vots[0].hi", offsetof(GpuVot, hi)}, {"vots[0].logSize", offsetof(GpuVot, logSize)},
        {"vots[0].p", offsetof(GpuVot, p)},   {"vots[0].lowerBound", offsetof(GpuVot, lowerBound)},
        {"vots[0].c[0]", offsetof(GpuVot, c)}};
    std::ostringstream table;
    table << "field | GLSL offset | C++ offset | GLSL top-level stride | sizeof(GpuVot)\n";
    bool ok = true;
    for (const Field& f : fields) {
        const GLuint index = glGetProgramResourceIndex(program.get(), GL_BUFFER_VARIABLE, f.glslName);
        ASSERT_NE(index, GL_INVALID_INDEX) << f.glslName << " not active in the program";
        const GLenum props[] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE, GL_ARRAY_STRIDE};
        GLint values[3] = {-1, -1, -1};
        glGetProgramResourceiv(program.get(), GL_BUFFER_VARIABLE, index, 3, props, 3, nullptr, values);
        table << f.glslName << " | " << values[0] << " | " << f.cppOffset << " | " << values[1] << " | "
              << sizeof(GpuVot) << "\n";
        ok = ok && values[0] == static_cast<GLint>(f.cppOffset) &&
             values[1] == static_cast<GLint>(sizeof(GpuVot));
        if (std::string(f.glslName) == "vots[0].c[0]")
            ok = ok && values[2] == static_cast<GLint>(sizeof(float));
    }
    EXPECT_TRUE(ok) << table.str();
}

TEST(GpuLayout, GeneratedTaylorFollowsMonomialOrder) {
    // The generator writes one line per monomial, in MONOMIAL_NAMES order, into the MIP shader.
    const std::string source = shaders::VOT_MIP_FRAG;
    std::size_t pos = 0;
    for (std::size_t i = 0; i < vots::fit::MONOMIAL_COUNT; ++i) {
        const std::string line = "g += c[" + std::to_string(i) + "] *";
        const std::size_t at = source.find(line, pos);
        ASSERT_NE(at, std::string::npos) << line;
        const std::size_t end = source.find('\n', at);
        EXPECT_NE(source.substr(at, end - at).find(std::string("// ") + vots::fit::MONOMIAL_NAMES[i]),
                  std::string::npos);
        pos = end;
    }
}
