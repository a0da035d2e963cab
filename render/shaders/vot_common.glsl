// Per-instance Vot records (std430 mirror: render/include/vots/render/GpuLayout.h) and the visible list.
#include "contract.glsl"

struct GpuVot {
    vec3 lo;          // box minimum corner, index space            (offset 0)
    float upperBound; // upper bound of the polynomial over the box (offset 12)
    vec3 hi;          // box maximum corner, index space            (offset 16)
    float logSize;    // log2 geometric-mean edge length, cells     (offset 28)
    vec3 p;           // expansion point, index space               (offset 32)
    float lowerBound; // lower bound over the box                   (offset 44)
    float c[TAYLOR_TERMS]; // Taylor coefficients, canonical order       (offset 48)
};
layout(std430, binding = VOT_BUFFER_BINDING) readonly buffer VotBuffer { GpuVot vots[]; };
layout(std430, binding = INDEX_BUFFER_BINDING) readonly buffer IndexBuffer { uint visible[]; };

// BOX_SLACK and CLIP_SLACK (contract.glsl): why boxes are grown, ShaderContract.h.
