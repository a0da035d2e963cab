// The C++ side of the shader contract matches what the linked programs report (record layout, units, work
// group).
#include "GlObjects.h"
#include "RenderTestSupport.h"
#include "ShaderContract.h"
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

namespace {
GLint samplerUnit(const GlProgram& program, const char* name) {
    const GLint location = glGetUniformLocation(program.get(), name);
    EXPECT_NE(location, -1) << name << " not active in the program";
    GLint unit = -1;
    glGetUniformiv(program.get(), location, &unit);
    return unit;
}
} // namespace

TEST(GpuLayout, ContractValuesArePinned) {
    // Changing one of these changes the file-independent GPU layout; this test is the reminder to change
    // the other side's assumptions (record packing, culling bounds) with it.
    EXPECT_EQ(VOT_TEXELS * 16, sizeof(GpuVot));
    EXPECT_EQ(WALK_RECORD_TEXELS * 16, 64u); // one cache line per walk record
    EXPECT_EQ(WALK_GROUP_SIDE, 8);
    EXPECT_EQ(BOX_SLACK, 1e-3f);
    EXPECT_EQ(CLIP_SLACK, 5e-5f);
    // The generated GLSL holds the same numbers, written once per shader.
    const std::string walk = shaders::VOT_WALK_COMP;
    EXPECT_NE(walk.find("const int WALK_RECORD_TEXELS = " + std::to_string(WALK_RECORD_TEXELS) + ";"),
              std::string::npos);
    const std::size_t first = walk.find("const int TAYLOR_TERMS = ");
    ASSERT_NE(first, std::string::npos);
    EXPECT_EQ(walk.find("const int TAYLOR_TERMS = ", first + 1), std::string::npos);
}

TEST(GpuLayout, LinkedProgramsUseTheContractsUnits) {
    vots::test::glContext();
    const GlProgram fragmentWalk = buildProgram(shaders::WALK_BOX_VERT, shaders::VOT_WALK_FRAG, "walk test");
    const GlProgram computeWalk = buildComputeProgram(shaders::VOT_WALK_COMP, "compute walk test");
    for (const GlProgram* walk : {&fragmentWalk, &computeWalk}) {
        EXPECT_EQ(samplerUnit(*walk, "uCellTable"), WALK_CELL_TABLE_UNIT);
        EXPECT_EQ(samplerUnit(*walk, "uBrickMax"), WALK_BRICK_MAX_UNIT);
        EXPECT_EQ(samplerUnit(*walk, "uVotBox"), WALK_VOT_BOX_UNIT);
        EXPECT_EQ(samplerUnit(*walk, "uWalkRecord"), WALK_RECORD_UNIT);
    }
    GLint group[3] = {0, 0, 0};
    glGetProgramiv(computeWalk.get(), GL_COMPUTE_WORK_GROUP_SIZE, group);
    EXPECT_EQ(group[0], WALK_GROUP_SIDE);
    EXPECT_EQ(group[1], WALK_GROUP_SIDE);
    EXPECT_EQ(group[2], 1);
    EXPECT_EQ(samplerUnit(computeWalk, "uTarget"), WALK_TARGET_IMAGE_UNIT);

    const GlProgram mip = buildProgram(shaders::VOT_BOX_VERT, shaders::VOT_MIP_FRAG, "raster test");
    EXPECT_EQ(samplerUnit(mip, "uVotData"), static_cast<GLint>(VOT_TEXTURE_UNIT));
    EXPECT_EQ(samplerUnit(mip, "uPrevMax"), PREV_MAX_UNIT);
    for (const auto& [name, binding] :
         {std::pair{"VotBuffer", VOT_BUFFER_BINDING}, std::pair{"IndexBuffer", INDEX_BUFFER_BINDING}}) {
        const GLuint index = glGetProgramResourceIndex(mip.get(), GL_SHADER_STORAGE_BLOCK, name);
        ASSERT_NE(index, GL_INVALID_INDEX) << name;
        const GLenum prop = GL_BUFFER_BINDING;
        GLint value = -1;
        glGetProgramResourceiv(mip.get(), GL_SHADER_STORAGE_BLOCK, index, 1, &prop, 1, nullptr, &value);
        EXPECT_EQ(value, static_cast<GLint>(binding)) << name;
    }
}
