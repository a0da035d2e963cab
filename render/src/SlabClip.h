// Sets the slab uniforms of ray_common.glsl for one frame (off when the frame has no slab).
#pragma once

#include "GlObjects.h"

#include "vots/render/Camera.h"
#include "vots/render/Slab.h"

#include <optional>

namespace vots::render {

void setSlabUniforms(GLuint program, const std::optional<Slab>& slab, const Camera& camera,
                     const SceneBounds& bounds);
/// The same from planes computed once for a frame (nullopt: no slab).
void setSlabUniforms(GLuint program, const std::optional<SlabPlanes>& planes);

} // namespace vots::render
