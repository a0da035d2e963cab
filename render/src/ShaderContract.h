// The numbers C++ and GLSL must agree on; vots_embed_shaders writes them into contract.glsl for the shaders.
#pragma once

#include "VotWalkGrid.h"
#include "WalkRecord.h"

#include "vots/fit/Monomials.h"
#include "vots/render/GpuLayout.h"

#include <array>
#include <cstddef>
#include <string_view>

namespace vots::render {

/// Index units by which boxes are grown for rasterising (BOX_SLACK) and for clipping the ray (CLIP_SLACK):
/// closes cracks where a pixel centre lies exactly on a face shared by two boxes (rasteriser edge rules
/// and float rounding of the ray origin, ~1e-5 voxel, could reject it in both). CLIP_SLACK is kept small
/// because a grazing ray may run a long way inside it, past the edge of the data. The walk's grid box is
/// grown by BOX_SLACK too.
inline constexpr float BOX_SLACK = 1e-3f;
inline constexpr float CLIP_SLACK = 5e-5f;

/// Texture units of the walk's buffer textures and the image unit of the compute walk's target.
inline constexpr int WALK_CELL_TABLE_UNIT = 0;
inline constexpr int WALK_BRICK_MAX_UNIT = 1;
inline constexpr int WALK_VOT_BOX_UNIT = 2;
inline constexpr int WALK_RECORD_UNIT = 3;
inline constexpr int WALK_TARGET_IMAGE_UNIT = 0;
/// The compute walk's work group: WALK_GROUP_SIDE^2 pixels.
inline constexpr int WALK_GROUP_SIDE = 8;
/// What the walk takes along each ray (uMode of vot_walk.glsl): the max; the max of the negated
/// polynomials (the min, negated, so that the max's culling serves it unchanged); the integral; only the
/// length of the ray's part the mean divides by (no walk), for compositing means across ranks.
inline constexpr int WALK_MODE_MAX = 0;
inline constexpr int WALK_MODE_MIN = 1;
inline constexpr int WALK_MODE_MEAN = 2;
inline constexpr int WALK_MODE_LENGTH = 3;
/// Texture unit of the raster MIP's copy of the max image after the last batch.
inline constexpr int PREV_MAX_UNIT = 0;

/// One named constant of the contract, as the generator writes it.
struct ContractInt {
    std::string_view name;
    long long value;
};
struct ContractFloat {
    std::string_view name;
    float value;
};

inline constexpr std::array<ContractInt, 18> CONTRACT_INTS{{
    {"TAYLOR_TERMS", static_cast<long long>(fit::MONOMIAL_COUNT)},
    {"VOT_BUFFER_BINDING", VOT_BUFFER_BINDING},
    {"INDEX_BUFFER_BINDING", INDEX_BUFFER_BINDING},
    {"VOT_TEXTURE_UNIT", VOT_TEXTURE_UNIT},
    {"VOT_TEXELS", VOT_TEXELS},
    {"WALK_RECORD_TEXELS", static_cast<long long>(WALK_RECORD_TEXELS)},
    {"WALK_CELL_TABLE_UNIT", WALK_CELL_TABLE_UNIT},
    {"CELL_TABLE_CODE_BITS", CELL_TABLE_CODE_BITS},
    {"WALK_BRICK_MAX_UNIT", WALK_BRICK_MAX_UNIT},
    {"WALK_VOT_BOX_UNIT", WALK_VOT_BOX_UNIT},
    {"WALK_RECORD_UNIT", WALK_RECORD_UNIT},
    {"WALK_TARGET_IMAGE_UNIT", WALK_TARGET_IMAGE_UNIT},
    {"WALK_GROUP_SIDE", WALK_GROUP_SIDE},
    {"PREV_MAX_UNIT", PREV_MAX_UNIT},
    {"WALK_MODE_MAX", WALK_MODE_MAX},
    {"WALK_MODE_MIN", WALK_MODE_MIN},
    {"WALK_MODE_MEAN", WALK_MODE_MEAN},
    {"WALK_MODE_LENGTH", WALK_MODE_LENGTH},
}};
inline constexpr std::array<ContractFloat, 2> CONTRACT_FLOATS{{
    {"BOX_SLACK", BOX_SLACK},
    {"CLIP_SLACK", CLIP_SLACK},
}};

} // namespace vots::render
