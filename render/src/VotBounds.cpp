// Bernstein bounds of degree <= 3 Vots over their boxes (per axis degree 3, 4x4x4 coefficients).
#include "VotBounds.h"

#include <algorithm>
#include <cmath>

namespace vots::render {

namespace {

// Values at t = 0, 1/3, 2/3, 1 -> cubic Bernstein coefficients (inverse of the collocation matrix
// B_j(t_i) = C(3,j) t_i^j (1-t_i)^(3-j); rows 0 and 3 are the endpoints, the middle 2x2 solved by hand).
void valuesToBernstein(double v0, double v1, double v2, double v3, double* b) {
    const double r1 = 27.0 * v1 - 8.0 * v0 - v3;
    const double r2 = 27.0 * v2 - v0 - 8.0 * v3;
    b[0] = v0;
    b[1] = (2.0 * r1 - r2) / 18.0;
    b[2] = (2.0 * r2 - r1) / 18.0;
    b[3] = v3;
}

double evaluate(const fit::Vot& vot, const double d[3]) {
    double sum = 0.0;
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
        double term = vot.c[i];
        for (int axis = 0; axis < 3; ++axis)
            for (int k = 0; k < fit::MONOMIAL_EXPONENTS[i][static_cast<std::size_t>(axis)]; ++k)
                term *= d[axis];
        sum += term;
    }
    return sum;
}

} // namespace

VotBounds computeVotBounds(const fit::Vot& vot) {
    // Sample the polynomial on a 4x4x4 lattice over the box (local t in [0,1]^3), then transform
    // along each axis into Bernstein coefficients.
    double grid[4][4][4];
    double slackSum = 0.0;
    double h[3];
    for (int axis = 0; axis < 3; ++axis)
        h[axis] = std::max(std::abs(vot.box.lo[axis] - double(vot.p[axis])),
                           std::abs(vot.box.hi[axis] - double(vot.p[axis])));
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
        double term = std::abs(double(vot.c[i]));
        for (int axis = 0; axis < 3; ++axis)
            term *= std::pow(h[axis] + 1.0, fit::MONOMIAL_EXPONENTS[i][static_cast<std::size_t>(axis)]);
        slackSum += term;
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                const int t[3] = {i, j, k};
                double d[3];
                for (int axis = 0; axis < 3; ++axis)
                    d[axis] = vot.box.lo[axis] + (vot.box.hi[axis] - vot.box.lo[axis]) * (t[axis] / 3.0) -
                              double(vot.p[axis]);
                grid[i][j][k] = evaluate(vot, d);
            }
    double b[4];
    for (int j = 0; j < 4; ++j)
        for (int k = 0; k < 4; ++k) {
            valuesToBernstein(grid[0][j][k], grid[1][j][k], grid[2][j][k], grid[3][j][k], b);
            for (int i = 0; i < 4; ++i)
                grid[i][j][k] = b[i];
        }
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) {
            valuesToBernstein(grid[i][0][k], grid[i][1][k], grid[i][2][k], grid[i][3][k], b);
            for (int j = 0; j < 4; ++j)
                grid[i][j][k] = b[j];
        }
    VotBounds out;
    out.lower = INFINITY;
    out.upper = -INFINITY;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            valuesToBernstein(grid[i][j][0], grid[i][j][1], grid[i][j][2], grid[i][j][3], b);
            for (double v : b) {
                out.lower = std::min(out.lower, v);
                out.upper = std::max(out.upper, v);
            }
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
