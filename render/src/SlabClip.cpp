// Sets the slab uniforms of ray_common.glsl for one frame (off when the frame has no slab).
#include "SlabClip.h"

namespace vots::render {

void setSlabUniforms(GLuint program, const std::optional<Slab>& slab, const Camera& camera,
                     const SceneBounds& bounds) {
    glProgramUniform1i(program, glGetUniformLocation(program, "uSlabOn"), slab ? 1 : 0);
    if (!slab) return;
    const SlabPlanes planes = slabPlanesInIndexSpace(*slab, camera, bounds);
    glProgramUniform4f(program, glGetUniformLocation(program, "uSlabPlane"), float(planes.normal[0]),
                       float(planes.normal[1]), float(planes.normal[2]), float(planes.offset));
    glProgramUniform2f(program, glGetUniformLocation(program, "uSlabRange"), float(planes.lo),
                       float(planes.hi));
}

} // namespace vots::render
