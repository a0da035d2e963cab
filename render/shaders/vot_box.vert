#version 450 core
// One unit cube per instance, stretched to its Vot's box; the fragment shader does the real work.
#include "vot_common.glsl"
#include "unit_cube.glsl"

uniform mat4 uIndexToClip;
uniform uint uFirst;     // first entry of this batch (in `visible`, or in `vots` when uUseList == 0)
uniform int uUseList;    // 1: instance i draws vots[visible[uFirst + i]]; 0: vots[uFirst + i]

flat out uint vVot;

void main() {
    uint id = uUseList != 0 ? visible[uFirst + uint(gl_InstanceID)] : uFirst + uint(gl_InstanceID);
    // Grow each box by a hair so boxes that share a face (or meet at a T-junction) always cover the
    // pixels on their common edge; a pixel covered twice is harmless under MAX/MIN blending.
    vec3 pos = mix(vots[id].lo - BOX_SLACK, vots[id].hi + BOX_SLACK, cubeCorner(gl_VertexID));
    gl_Position = uIndexToClip * vec4(pos, 1.0);
    vVot = id;
}
