// The canonical order of the 20 Taylor monomials (docs/DESIGN.md §1), used by file, shaders and tests.
#pragma once

#include <array>
#include <cstddef>

namespace vots::fit {

inline constexpr std::size_t MONOMIAL_COUNT = 20;

/// Exponents (a_x, a_y, a_z) of each monomial d^a, in the order
/// 1 | x y z | xx yy zz xy xz yz | xxx yyy zzz xxy xxz xyy yyz xzz yzz xyz.
// clang-format off
inline constexpr std::array<std::array<int, 3>, MONOMIAL_COUNT> MONOMIAL_EXPONENTS{{
    {0, 0, 0},                                                                         //
    {1, 0, 0}, {0, 1, 0}, {0, 0, 1},                                                   //
    {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1},                  //
    {3, 0, 0}, {0, 3, 0}, {0, 0, 3}, {2, 1, 0}, {2, 0, 1}, {1, 2, 0}, {0, 2, 1},       //
    {1, 0, 2}, {0, 1, 2}, {1, 1, 1},
}};

inline constexpr std::array<const char*, MONOMIAL_COUNT> MONOMIAL_NAMES{
    "1",  "x",  "y",  "z",   "xx",  "yy",  "zz",  "xy",  "xz",  "yz",
    "xxx", "yyy", "zzz", "xxy", "xxz", "xyy", "yyz", "xzz", "yzz", "xyz"};
// clang-format on

constexpr int monomialDegree(std::size_t i) {
    return MONOMIAL_EXPONENTS[i][0] + MONOMIAL_EXPONENTS[i][1] + MONOMIAL_EXPONENTS[i][2];
}

/// Number of monomials of total degree <= degree (1, 4, 10, 20).
constexpr std::size_t monomialCountForDegree(int degree) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (monomialDegree(i) <= degree) ++n;
    return n;
}

/// Index of the monomial with the given exponents, or -1.
constexpr int monomialIndex(int ax, int ay, int az) {
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        if (MONOMIAL_EXPONENTS[i][0] == ax && MONOMIAL_EXPONENTS[i][1] == ay &&
            MONOMIAL_EXPONENTS[i][2] == az)
            return static_cast<int>(i);
    return -1;
}

static_assert(monomialCountForDegree(3) == 20 && monomialCountForDegree(2) == 10);
static_assert(monomialIndex(1, 1, 1) == 19 && monomialIndex(1, 0, 2) == 17);

} // namespace vots::fit
