// Sets the slab uniforms of ray_common.glsl for one frame (off when the frame has no slab).
#include "SlabClip.h"

namespace vots::render {

void setSlabUniforms(GLuint program, const std::optional<SlabPlanes>& planes) {
    glProgramUniform1i(program, glGetUniformLocation(program, "uSlabOn"), planes ? 1 : 0);
    if (!planes) return;
    glProgramUniform4f(program, glGetUniformLocation(program, "uSlabPlane"), float(planes->normal[0]),
                       float(planes->normal[1]), float(planes->normal[2]), float(planes->offset));
    glProgramUniform2f(program, glGetUniformLocation(program, "uSlabRange"), float(planes->lo),
                       float(planes->hi));
}

void setSlabUniforms(GLuint program, const std::optional<Slab>& slab, const Camera& camera,
                     const SceneBounds& bounds) {
    setSlabUniforms(program,
                    slab ? std::optional(slabPlanesInIndexSpace(*slab, camera, bounds)) : std::nullopt);
}

} // namespace vots::render
