#version 450 core
// Walk strategy as a compute shader: one invocation per pixel of the target. GPUs such as the H100 run
// fragment shaders on a few of their multiprocessors only, compute on all of them (bench/RESULTS.md).
#include "vot_walk.glsl"

layout(local_size_x = WALK_GROUP_SIDE, local_size_y = WALK_GROUP_SIDE) in;
layout(r32f, binding = WALK_TARGET_IMAGE_UNIT) uniform writeonly image2D uTarget;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(uViewport)))) return;
    imageStore(uTarget, pixel, vec4(walkPixel(vec2(pixel) + 0.5)));
}
