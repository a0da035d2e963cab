// Deterministic synthetic volumes for tests: random polynomials of degree <= 3 and seeded smooth noise.
#pragma once

#include "vots/fit/Monomials.h"
#include "vots/fit/Volume.h"

#include "SampleVolume.h"

#include <array>
#include <cmath>
#include <functional>
#include <random>

namespace vots::test {

/// A polynomial in global index coordinates around `centre`, in the canonical monomial order.
struct Polynomial {
    std::array<double, 3> centre{0.0, 0.0, 0.0};
    std::array<double, fit::MONOMIAL_COUNT> c{};

    double operator()(double x, double y, double z) const {
        const double d[3] = {x - centre[0], y - centre[1], z - centre[2]};
        double sum = 0.0;
        for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
            const auto& a = fit::MONOMIAL_EXPONENTS[i];
            sum += c[i] * std::pow(d[0], a[0]) * std::pow(d[1], a[1]) * std::pow(d[2], a[2]);
        }
        return sum;
    }
};

/// Random coefficients of total degree <= degree, scaled so each term stays O(amplitude) on the grid.
inline Polynomial randomPolynomial(int degree, const std::array<int, 3>& dims, unsigned seed,
                                   double amplitude = 100.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    Polynomial p;
    for (int a = 0; a < 3; ++a)
        p.centre[a] = 0.5 * (dims[a] - 1) + 0.3 * uniform(rng);
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
        if (fit::monomialDegree(i) > degree) continue;
        const auto& e = fit::MONOMIAL_EXPONENTS[i];
        double scale = amplitude;
        for (int a = 0; a < 3; ++a)
            scale /= std::pow(0.5 * dims[a], e[a]);
        p.c[i] = uniform(rng) * scale;
    }
    return p;
}

/// Uniform random samples in [lo, hi]: the hardest case, every cell different.
inline fit::Volume randomVolume(const std::array<int, 3>& dims, unsigned seed, double lo = 0.0,
                                double hi = 1000.0) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(lo, hi);
    return sampleVolume(dims, [&](int, int, int) { return uniform(rng); });
}

/// Trilinear interpolation of the grid at a point in index space.
inline double trilinear(const fit::Volume& v, double x, double y, double z) {
    const int i = std::min(static_cast<int>(x), v.dims[0] - 2);
    const int j = std::min(static_cast<int>(y), v.dims[1] - 2);
    const int k = std::min(static_cast<int>(z), v.dims[2] - 2);
    const double u = x - i, s = y - j, t = z - k;
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        sum += v.at(i + dx, j + dy, k + dz) * (dx ? u : 1 - u) * (dy ? s : 1 - s) * (dz ? t : 1 - t);
    }
    return sum;
}

} // namespace vots::test
