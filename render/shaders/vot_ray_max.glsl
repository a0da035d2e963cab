// Max of one Vot along a ray from its shared record (GpuLayout.h), for the raster MIP shader.
// Needs vot_common.glsl and ray_common.glsl included before it.
#include "cubic_ray_max.glsl"

// The Vot records of vots[] (GpuLayout.h) seen as a buffer texture, VOT_TEXELS RGBA32F texels per Vot: texel
// fetches gather all pixels' records at once, where llvmpipe loads SSBO data pixel by pixel.
layout(binding = VOT_TEXTURE_UNIT) uniform samplerBuffer uVotData;

// Max of Vot `vot` along origin + t dir, t in `range`, over its box grown by CLIP_SLACK. Returns false
// (value untouched) when the ray misses the box.
bool votRayMax(uint vot, vec3 origin, vec3 dir, vec2 range, out float value) {
    int base = int(vot) * VOT_TEXELS;
    float c[TAYLOR_TERMS];
    for (int k = 0; k < TAYLOR_TERMS / 4; ++k) {
        vec4 q = texelFetch(uVotData, base + 3 + k);
        c[4 * k] = q.x;
        c[4 * k + 1] = q.y;
        c[4 * k + 2] = q.z;
        c[4 * k + 3] = q.w;
    }
    vec3 lo = texelFetch(uVotData, base).xyz, hi = texelFetch(uVotData, base + 1).xyz;
    vec3 p = texelFetch(uVotData, base + 2).xyz;
    return cubicRayMax(c, lo, hi, p, vec3(1.0), origin, dir, range, value);
}
