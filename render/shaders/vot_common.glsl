// Per-instance Vot records (std430 mirror: render/include/vots/render/GpuLayout.h) and the visible list.
struct GpuVot {
    vec3 lo;          // box minimum corner, index space            (offset 0)
    float upperBound; // upper bound of the polynomial over the box (offset 12)
    vec3 hi;          // box maximum corner, index space            (offset 16)
    float logSize;    // log2 geometric-mean edge length, cells     (offset 28)
    vec3 p;           // expansion point, index space               (offset 32)
    float lowerBound; // lower bound over the box                   (offset 44)
    float c[20];      // Taylor coefficients, canonical order       (offset 48)
};
layout(std430, binding = 0) readonly buffer VotBuffer { GpuVot vots[]; };
layout(std430, binding = 1) readonly buffer IndexBuffer { uint visible[]; };

// Index units by which boxes are grown for rasterising (BOX_SLACK) and for clipping the ray (CLIP_SLACK):
// closes cracks where a pixel centre lies exactly on a face shared by two boxes (rasteriser edge rules
// and float rounding of the ray origin, ~1e-5 voxel, could reject it in both). CLIP_SLACK is kept small
// because a grazing ray may run a long way inside it, past the edge of the data.
const float BOX_SLACK = 1e-3;
const float CLIP_SLACK = 5e-5;
