#version 450 core
// Raster strategy: analytic MIP of one Vot along the pixel's ray (docs/DESIGN.md §5), max of a cubic over
// [tIn, tOut].
#include "vot_common.glsl"
#include "ray_common.glsl"
#include "vot_ray_max.glsl"

// The max image after the previous batch (culling), or -inf.
layout(binding = PREV_MAX_UNIT) uniform sampler2D uPrevMax;
uniform int uUsePrevMax;

flat in uint vVot;
layout(location = 0) out float outValue;

void main() {
    // A Vot whose bound cannot beat what the pixel already holds changes nothing: stop early.
    if (uUsePrevMax != 0 && vots[vVot].upperBound <= texelFetch(uPrevMax, ivec2(gl_FragCoord.xy), 0).r)
        discard;

    vec3 origin, dir;
    float farT;
    pixelRay(gl_FragCoord.xy, origin, dir, farT);
    vec2 range = clipRayToSlab(origin, dir, vec2(0.0, farT));
    float value;
    if (range.x > range.y || !votRayMax(vVot, origin, dir, range, value)) discard;
    outValue = value;
}
