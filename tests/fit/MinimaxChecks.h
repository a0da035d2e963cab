// What the minimax tests share: the test volumes, fit options, and a fit's Vots checked without the verifier.
#pragma once

#include "SyntheticFields.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"
#include "vots/fit/VolumeLoad.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vots::test {

using namespace vots::fit;

inline Volume loadShared(const std::string& name) {
    return loadVolume(std::string(VOTS_TEST_DATA_DIR) + "/" + name);
}

inline FitOptions options(float eps, int degree, FitNorm norm, Certify certify = Certify::Samples) {
    FitOptions o;
    o.eps = eps;
    o.degree = degree;
    o.norm = norm;
    o.certify = certify;
    return o;
}

/// The Vot's polynomial, evaluated here term by term from its float coefficients (not Vot::evaluate).
inline double evaluate(const Vot& vot, double x, double y, double z) {
    const double d[3] = {x - vot.p[0], y - vot.p[1], z - vot.p[2]};
    double sum = 0.0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        double term = static_cast<double>(vot.c[i]);
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < e[a]; ++k)
                term *= d[a];
        sum += term;
    }
    return sum;
}

/// The polynomial of scaled coefficients (over u = (x - centre) / half-extent) at index point (x, y, z).
inline double scaledPolynomial(const std::array<double, MONOMIAL_COUNT>& scaled, const Box& box, double x,
                               double y, double z) {
    const double u[3] = {(x - 0.5 * (box.lo[0] + box.hi[0])) / (0.5 * box.cells(0)),
                         (y - 0.5 * (box.lo[1] + box.hi[1])) / (0.5 * box.cells(1)),
                         (z - 0.5 * (box.lo[2] + box.hi[2])) / (0.5 * box.cells(2))};
    double p = 0.0;
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        const auto& e = MONOMIAL_EXPONENTS[i];
        p += scaled[i] * std::pow(u[0], e[0]) * std::pow(u[1], e[1]) * std::pow(u[2], e[2]);
    }
    return p;
}

/// The largest |P - value| of a polynomial of scaled coefficients over the box's samples and, with
/// `halfSteps`, every point of its half-integer lattice (edge midpoints, face and cell centres) against
/// the mean of the samples at the corners of its edge, face or cell.
inline double largestLatticeResidual(const Volume& volume, const Box& box,
                                     const std::array<double, MONOMIAL_COUNT>& scaled, bool halfSteps) {
    const int step = halfSteps ? 1 : 2;
    double worst = 0.0;
    for (int tz = 2 * box.lo[2]; tz <= 2 * box.hi[2]; tz += step)
        for (int ty = 2 * box.lo[1]; ty <= 2 * box.hi[1]; ty += step)
            for (int tx = 2 * box.lo[0]; tx <= 2 * box.hi[0]; tx += step) {
                double sum = 0.0;
                int count = 0;
                for (int k = 0; k <= (tz & 1); ++k)
                    for (int j = 0; j <= (ty & 1); ++j)
                        for (int i = 0; i <= (tx & 1); ++i, ++count)
                            sum += volume.at(tx / 2 + i, ty / 2 + j, tz / 2 + k);
                const double p = scaledPolynomial(scaled, box, 0.5 * tx, 0.5 * ty, 0.5 * tz);
                worst = std::max(worst, std::abs(p - sum / count));
            }
    return worst;
}

struct Independent {
    std::size_t samples = 0;
    std::size_t beyondEps = 0;     // samples beyond eps(sample) + the float allowance
    std::size_t uncovered = 0;     // foreground cells in no box
    std::size_t doublyCovered = 0; // cells in two boxes
    double worstCellPoint = 0.0;   // the largest |P - trilinear| / eps at edge midpoints and cell centres
};

/// Every sample of every Vot, and the cover of the foreground cells, recomputed without the verifier.
inline Independent recompute(const VotSpace& space, const Volume& volume, const EpsField& eps,
                             float background, bool cellPoints) {
    Independent out;
    const int cx = volume.dims[0] - 1, cy = volume.dims[1] - 1, cz = volume.dims[2] - 1;
    std::vector<std::uint8_t> covered(static_cast<std::size_t>(cx) * cy * cz, 0);
    for (const Vot& vot : space.vots) {
        const Box& b = vot.box;
        for (int z = b.lo[2]; z <= b.hi[2]; ++z)
            for (int y = b.lo[1]; y <= b.hi[1]; ++y)
                for (int x = b.lo[0]; x <= b.hi[0]; ++x) {
                    const double f = volume.at(x, y, z);
                    const double r = std::abs(evaluate(vot, x, y, z) - f);
                    ++out.samples;
                    if (r > eps.at(x, y, z) + FLOAT_ALLOWANCE * (1.0 + std::abs(f))) ++out.beyondEps;
                }
        for (int z = b.lo[2]; z < b.hi[2]; ++z)
            for (int y = b.lo[1]; y < b.hi[1]; ++y)
                for (int x = b.lo[0]; x < b.hi[0]; ++x) {
                    std::uint8_t& c =
                        covered[static_cast<std::size_t>(x) +
                                static_cast<std::size_t>(cx) * (y + static_cast<std::size_t>(cy) * z)];
                    if (c) ++out.doublyCovered;
                    c = 1;
                }
        if (!cellPoints) continue;
        for (int zi = 2 * b.lo[2]; zi <= 2 * b.hi[2]; ++zi)
            for (int yi = 2 * b.lo[1]; yi <= 2 * b.hi[1]; ++yi)
                for (int xi = 2 * b.lo[0]; xi <= 2 * b.hi[0]; ++xi) {
                    const int halves = (xi & 1) + (yi & 1) + (zi & 1);
                    if (halves != 1 && halves != 3) continue;
                    const double x = 0.5 * xi, y = 0.5 * yi, z = 0.5 * zi;
                    out.worstCellPoint = std::max(
                        out.worstCellPoint,
                        std::abs(evaluate(vot, x, y, z) - trilinear(volume, x, y, z)) / eps.at(x, y, z));
                }
    }
    for (int z = 0; z < cz; ++z)
        for (int y = 0; y < cy; ++y)
            for (int x = 0; x < cx; ++x) {
                bool foreground = false;
                for (int c = 0; c < 8; ++c)
                    foreground = foreground ||
                                 volume.at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)) >= background;
                if (foreground &&
                    !covered[static_cast<std::size_t>(x) +
                             static_cast<std::size_t>(cx) * (y + static_cast<std::size_t>(cy) * z)])
                    ++out.uncovered;
            }
    return out;
}

} // namespace vots::test
