// std430 mirror of the per-instance Vot record read by the Vot shaders (SSBO binding VOT_BUFFER_BINDING).
#pragma once

#include "vots/fit/Monomials.h"

#include <cstddef>
#include <cstdint>

namespace vots::render {

inline constexpr unsigned VOT_BUFFER_BINDING = 0;   // SSBO "VotBuffer { GpuVot vots[]; }"
inline constexpr unsigned INDEX_BUFFER_BINDING = 1; // SSBO "IndexBuffer { uint visible[]; }"

/// One Vot as the shaders see it (GLSL struct GpuVot in vot_common.glsl). All positions in grid
/// index space; values in data units. Records are stored in space order (VotOrder.h) when the walk
/// draws the MIP, else by descending upperBound, the order Raster's batch culling wants.
struct GpuVot {
    float lo[3];      // 12B (0)   box minimum corner, index space
    float upperBound; //  4B (12)  certified upper bound of the polynomial over the box (+ float margin)
    float hi[3];      // 12B (16)  box maximum corner, index space
    float logSize;    //  4B (28)  log2 of the box's geometric-mean edge length in cells (density view)
    float p[3];       // 12B (32)  expansion point P, index space
    float lowerBound; //  4B (44)  lower bound of the polynomial over the box
    float c[vots::fit::MONOMIAL_COUNT]; // 80B (48) Taylor coefficients, canonical order (Monomials.h)
};                                      // 128B total, array stride 128

static_assert(sizeof(GpuVot) == 128);
/// The raster MIP shader also reads the records as a buffer texture of RGBA32F texels (uVotData, texture unit
/// VOT_TEXTURE_UNIT): VOT_TEXELS texels per Vot, the coefficients four per texel.
inline constexpr unsigned VOT_TEXTURE_UNIT = 3;
inline constexpr unsigned VOT_TEXELS = sizeof(GpuVot) / 16;
static_assert(VOT_TEXELS == 8 && vots::fit::MONOMIAL_COUNT % 4 == 0);
static_assert(offsetof(GpuVot, lo) == 0 && offsetof(GpuVot, upperBound) == 12);
static_assert(offsetof(GpuVot, hi) == 16 && offsetof(GpuVot, logSize) == 28);
static_assert(offsetof(GpuVot, p) == 32 && offsetof(GpuVot, lowerBound) == 44);
static_assert(offsetof(GpuVot, c) == 48);

} // namespace vots::render
