// The CPU splat's inner loop: one Vot's exact max along the rays of a rectangle of pixels, 8 at a time.
#pragma once

#include "vots/fit/Monomials.h"

namespace vots::render {

/// A Vot as the splat's kernel reads it: its box grown by CLIP_SLACK (as the GL shaders clip), its
/// expansion point and coefficients (the fit's float32, as the raster strategy evaluates them).
struct SplatVot {
    float lo[3];
    float hi[3];
    float p[3];
    float c[fit::MONOMIAL_COUNT];
};

/// One frame's rays, rebuilt per pixel as ray_common.glsl's pixelRay does (the same float arithmetic, so
/// the same rays): ndc = 2 X / width - 1 for the pixel centre X (window coordinates, row 0 at the
/// bottom), the near point clipToIndex (ndc, -1, 1) and the far one clipToIndex (ndc, 1, 1); the ray
/// starts on the near plane (t = 0), unit direction, and ends on the far one.
struct SplatFrame {
    int width = 0;
    int height = 0;
    float clipToIndex[16]; // column-major
    // The slab (SlabPlanes): a point x counts when slabLo <= dot(slabNormal, x) + slabOffset <= slabHi.
    bool slabOn = false;
    float slabNormal[3], slabOffset, slabLo, slabHi;
    // The cell domain grown by CLIP_SLACK, as the walk takes a Vot's max inside it; off for the whole grid.
    bool domainOn = false;
    float domainLo[3], domainHi[3];
};

/// Raises best[y * width + x], for x in [x0, x1] and y in [y0, y1], to the max of `vot` along that
/// pixel's ray where the ray meets the Vot's box and best is below `upper` (the Vot's upper bound, which
/// covers a float evaluation so that culling by it never changes the image, or +inf to evaluate every
/// pixel). Returns whether any pixel rose. Uses AVX2 and FMA where the CPU has them
/// (picked at load time), SSE2 otherwise.
bool splatVot(const SplatFrame& frame, const SplatVot& vot, float upper, float* best, int x0, int x1, int y0,
              int y1);

} // namespace vots::render
