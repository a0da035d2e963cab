// Bernstein bounds of degree <= 3 Vots over their boxes (per axis degree 3, 4x4x4 coefficients).
#include "VotBounds.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vots::render {

namespace {

constexpr double BINOMIAL[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
// Cubic power basis -> Bernstein basis on [0, 1]: b_j = sum_{i <= j} C(j, i) / C(3, i) p_i.
constexpr double POWER_TO_BERNSTEIN[4][4] = {
    {1, 0, 0, 0}, {1, 1.0 / 3, 0, 0}, {1, 2.0 / 3, 1.0 / 3, 0}, {1, 1, 1, 1}};

// Converts a cubic's power coefficients p0..p3 in place to its Bernstein coefficients on [0, 1].
template <typename At> inline void toBernstein(At at) {
    const double p1 = at(1), p2 = at(2), p3 = at(3);
    at(1) = at(0) + p1 * POWER_TO_BERNSTEIN[1][1];
    at(2) = at(0) + p1 * POWER_TO_BERNSTEIN[2][1] + p2 * POWER_TO_BERNSTEIN[2][2];
    at(3) = at(0) + p1 + p2 + p3;
}

// Applies the conversion along every axis of a 4x4x4 coefficient tensor ([z][y][x]); constant strides
// let the compiler unroll it, which a table of pointers would not (every Vot's bounds are computed at
// upload).
void toBernstein3(double (&t)[4][4][4]) {
    for (int u = 0; u < 4; ++u)
        for (int v = 0; v < 4; ++v)
            toBernstein([&](int i) -> double& { return t[u][v][i]; });
    for (int u = 0; u < 4; ++u)
        for (int v = 0; v < 4; ++v)
            toBernstein([&](int i) -> double& { return t[u][i][v]; });
    for (int u = 0; u < 4; ++u)
        for (int v = 0; v < 4; ++v)
            toBernstein([&](int i) -> double& { return t[i][u][v]; });
}

} // namespace

VotBounds computeVotBounds(const fit::Vot& vot) {
    // On the box, X - p = a + w t per axis with t in [0, 1]. Expanding every monomial (a + w t)^e gives
    // the polynomial in t's power basis, which converts exactly to Bernstein coefficients per axis
    // (about 300 flops, far fewer than sampling 64 points and interpolating would take).
    double shift[3][4][4] = {}; // shift[axis][e][k]: coefficient of t^k in (a + w t)^e
    double slackPower[3][4];    // (h + 1)^e, h the largest distance from p along the axis
    for (int axis = 0; axis < 3; ++axis) {
        const double a = vot.box.lo[axis] - double(vot.p[axis]);
        const double w = vot.box.hi[axis] - vot.box.lo[axis];
        const double h = std::max(std::abs(a), std::abs(a + w));
        double aPow[4] = {1, a, a * a, a * a * a}, wPow[4] = {1, w, w * w, w * w * w};
        for (int e = 0; e < 4; ++e) {
            for (int k = 0; k <= e; ++k)
                shift[axis][e][k] = BINOMIAL[e][k] * aPow[e - k] * wPow[k];
            slackPower[axis][e] = e == 0 ? 1.0 : slackPower[axis][e - 1] * (h + 1.0);
        }
    }
    double t[4][4][4] = {}; // [z][y][x] power of t
    double slackSum = 0.0;
    // Unrolled over the monomials at compile time: with constant exponents the loops are short and
    // straight, where trip counts read from a table would not let the compiler unroll them.
    auto addMonomial = [&]<std::size_t M>(std::integral_constant<std::size_t, M>) {
        constexpr auto e = fit::MONOMIAL_EXPONENTS[M];
        const double c = vot.c[M];
        slackSum += std::abs(c) * slackPower[0][e[0]] * slackPower[1][e[1]] * slackPower[2][e[2]];
        for (int k = 0; k <= e[2]; ++k)
            for (int j = 0; j <= e[1]; ++j) {
                const double cjk = c * shift[2][e[2]][k] * shift[1][e[1]][j];
                for (int i = 0; i <= e[0]; ++i)
                    t[k][j][i] += cjk * shift[0][e[0]][i];
            }
    };
    [&]<std::size_t... M>(std::index_sequence<M...>) {
        (addMonomial(std::integral_constant<std::size_t, M>{}), ...);
    }
    (std::make_index_sequence<fit::MONOMIAL_COUNT>{});
    toBernstein3(t);
    VotBounds out;
    out.lower = INFINITY;
    out.upper = -INFINITY;
    for (const auto& plane : t)
        for (const auto& row : plane)
            for (double b : row) {
                out.lower = std::min(out.lower, b);
                out.upper = std::max(out.upper, b);
            }
    // Float32 evaluation on the GPU (and the bound's own rounding) stays well inside this slack.
    out.floatSlack = 4e-5 * slackSum + 1e-30;
    return out;
}

GpuVot makeGpuVot(const fit::Vot& vot, const VotBounds& bounds) {
    GpuVot g{};
    double logEdges = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
        g.lo[axis] = static_cast<float>(vot.box.lo[axis]);
        g.hi[axis] = static_cast<float>(vot.box.hi[axis]);
        g.p[axis] = vot.p[static_cast<std::size_t>(axis)];
        logEdges += std::log2(std::max(1, vot.box.hi[axis] - vot.box.lo[axis]));
    }
    g.logSize = static_cast<float>(logEdges / 3.0);
    // Rounded outward so the float bound still bounds.
    g.upperBound = std::nextafter(static_cast<float>(bounds.upper + bounds.floatSlack), INFINITY);
    g.lowerBound = std::nextafter(static_cast<float>(bounds.lower - bounds.floatSlack), -INFINITY);
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i)
        g.c[i] = vot.c[i];
    return g;
}

} // namespace vots::render
