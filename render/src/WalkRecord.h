// The Walk strategy's copy of a Vot: 64 bytes, one cache line, where the shared record takes two.
#pragma once

#include "vots/fit/Vot.h"

#include <array>
#include <cstddef>
#include <cstdint>

namespace vots::render {

/// Four RGBA32UI texels (uWalkRecord in vot_walk.glsl). The walk waits on the memory of the Vots it
/// evaluates more than on their arithmetic (bench/RESULTS.md), so the record is halved:
///   words 0-2   box corners in cells, 16 bits each (as the walk's box table packs them)
///   word 3      c_0, the value at the box centre (float)
///   words 4-6   the gradient terms (float)
///   word 7      the quantum q (float)
///   words 8-15  the 16 second- and third-order terms, two signed 16-bit multiples of q per word
///               (low half first), in the canonical monomial order
/// The polynomial is re-expanded around the box centre m and written in the box's own coordinates
/// u = (X - m) / h, h the half sides, so every monomial lies in [-1, 1] inside the box and each term's
/// rounding to a multiple of q moves the value by at most q / 2 anywhere in it.
inline constexpr std::size_t WALK_RECORD_WORDS = 16;
inline constexpr std::size_t WALK_RECORD_TEXELS = WALK_RECORD_WORDS / 4;

struct WalkRecord {
    std::array<std::uint32_t, WALK_RECORD_WORDS> words{};
    /// Bound on |record polynomial - Vot polynomial| over the box (grown by the shader's clip slack),
    /// before float rounding: the sum of the 16 terms' roundings, at most 8 q, so at most 2.5e-4 of
    /// the largest second- or third-order term.
    double maxError = 0.0;
};

/// The record of `vot`, whose box must fit the walk's 16-bit cell coordinates.
WalkRecord makeWalkRecord(const fit::Vot& vot);

/// The coefficients a record holds, in box coordinates (for tests: what the shader decodes).
std::array<double, fit::MONOMIAL_COUNT> walkRecordCoefficients(const WalkRecord& record);

} // namespace vots::render
