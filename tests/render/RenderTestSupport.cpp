// Implementation of the renderer test helpers and the test main (creates the GL context once).
#include "RenderTestSupport.h"

#include "vots/fit/Fitter.h"
#include "vots/fit/Monomials.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/Png.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

namespace vots::test {

namespace {
std::unique_ptr<render::EglContext> gContext;
std::string gContextError;
} // namespace

render::EglContext& glContext() {
    if (!gContext) throw std::runtime_error("no GL context: " + gContextError);
    return *gContext;
}

double Polynomial::operator()(double x, double y, double z) const {
    const double d[3] = {x - centre[0], y - centre[1], z - centre[2]};
    double sum = 0.0;
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
        double term = c[i];
        for (int a = 0; a < 3; ++a)
            for (int k = 0; k < fit::MONOMIAL_EXPONENTS[i][static_cast<std::size_t>(a)]; ++k)
                term *= d[a];
        sum += term;
    }
    return sum;
}

Polynomial randomPolynomial(int degree, int n, double amplitude, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Polynomial p;
    p.centre = {0.5 * (n - 1), 0.5 * (n - 1), 0.5 * (n - 1)};
    const double half = 0.5 * (n - 1);
    for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
        const int deg = fit::monomialDegree(i);
        if (deg > degree) continue;
        p.c[i] = static_cast<float>(amplitude * u(rng) / std::pow(half, deg));
    }
    return p;
}

fit::VotSpace cellVotSpace(const fit::Volume& volume) {
    fit::VotSpace space;
    space.dims = volume.dims;
    space.origin = volume.origin;
    space.spacing = volume.spacing;
    space.degree = 3;
    for (int z = 0; z + 1 < volume.dims[2]; ++z)
        for (int y = 0; y + 1 < volume.dims[1]; ++y)
            for (int x = 0; x + 1 < volume.dims[0]; ++x) {
                fit::Vot vot;
                vot.box = {{x, y, z}, {x + 1, y + 1, z + 1}};
                vot.p = {x + 0.5f, y + 0.5f, z + 0.5f};
                double c = 0, cx = 0, cy = 0, cz = 0, cxy = 0, cxz = 0, cyz = 0, cxyz = 0;
                for (int k = 0; k < 2; ++k)
                    for (int j = 0; j < 2; ++j)
                        for (int i = 0; i < 2; ++i) {
                            const double f = volume.at(x + i, y + j, z + k);
                            const double si = 2 * i - 1, sj = 2 * j - 1, sk = 2 * k - 1;
                            c += f / 8;
                            cx += si * f / 4, cy += sj * f / 4, cz += sk * f / 4;
                            cxy += si * sj * f / 2, cxz += si * sk * f / 2, cyz += sj * sk * f / 2;
                            cxyz += si * sj * sk * f;
                        }
                vot.c[0] = float(c), vot.c[1] = float(cx), vot.c[2] = float(cy), vot.c[3] = float(cz);
                vot.c[fit::monomialIndex(1, 1, 0)] = float(cxy);
                vot.c[fit::monomialIndex(1, 0, 1)] = float(cxz);
                vot.c[fit::monomialIndex(0, 1, 1)] = float(cyz);
                vot.c[fit::monomialIndex(1, 1, 1)] = float(cxyz);
                space.vots.push_back(vot);
            }
    return space;
}

// Re-expands the polynomial around a new centre: Taylor coefficients are derivatives / a!, which we
// get exactly by finite differences-free symbolic shifting (binomial expansion of each monomial).
fit::VotSpace polynomialVotSpace(const Polynomial& p, const std::array<int, 3>& dims, int side,
                                 float offCentre) {
    fit::VotSpace space;
    space.dims = dims;
    space.degree = 3;
    auto binom = [](int n, int k) { return (n == 3 && (k == 1 || k == 2)) ? 3 : (n == 2 && k == 1 ? 2 : 1); };
    for (int z = 0; z + 1 < dims[2]; z += side)
        for (int y = 0; y + 1 < dims[1]; y += side)
            for (int x = 0; x + 1 < dims[0]; x += side) {
                fit::Vot vot;
                vot.box = {{x, y, z},
                           {std::min(x + side, dims[0] - 1), std::min(y + side, dims[1] - 1),
                            std::min(z + side, dims[2] - 1)}};
                double q[3];
                for (int a = 0; a < 3; ++a) {
                    vot.p[a] = 0.5f * float(vot.box.lo[a] + vot.box.hi[a]) + offCentre;
                    q[a] = vot.p[a] - p.centre[a]; // new centre relative to the old one
                }
                // (q + d)^a = sum_b C(a,b) q^(a-b) d^b per axis
                std::array<double, 20> c{};
                for (std::size_t i = 0; i < fit::MONOMIAL_COUNT; ++i) {
                    const auto& e = fit::MONOMIAL_EXPONENTS[i];
                    for (int bx = 0; bx <= e[0]; ++bx)
                        for (int by = 0; by <= e[1]; ++by)
                            for (int bz = 0; bz <= e[2]; ++bz) {
                                const double w = binom(e[0], bx) * binom(e[1], by) * binom(e[2], bz) *
                                                 std::pow(q[0], e[0] - bx) * std::pow(q[1], e[1] - by) *
                                                 std::pow(q[2], e[2] - bz);
                                c[static_cast<std::size_t>(fit::monomialIndex(bx, by, bz))] += p.c[i] * w;
                            }
                }
                for (std::size_t i = 0; i < 20; ++i)
                    vot.c[i] = static_cast<float>(c[i]);
                space.vots.push_back(vot);
            }
    return space;
}

render::Camera obliqueCamera(render::Projection projection) {
    render::Camera c;
    c.azimuthDeg = 31;
    c.elevationDeg = 23;
    c.zoom = 1.3;
    c.projection = projection;
    return c;
}

RayProfile cpuRayProfile(const render::CameraMatrices& m, const std::array<int, 3>& dims, int width,
                         int height, int px, int py, const std::function<double(double, double, double)>& f,
                         int samples, const std::optional<render::SlabPlanes>& slab) {
    // Pixel (px, py) with py counted from the top, as in FloatImage.
    const double ndc[2] = {(px + 0.5) / width * 2 - 1, 1 - (py + 0.5) / height * 2};
    auto unproject = [&](double z, double out[3]) {
        double r[4];
        for (int row = 0; row < 4; ++row)
            r[row] = m.clipToIndex[row] * ndc[0] + m.clipToIndex[4 + row] * ndc[1] +
                     m.clipToIndex[8 + row] * z + m.clipToIndex[12 + row];
        for (int a = 0; a < 3; ++a)
            out[a] = r[a] / r[3];
    };
    double a[3], b[3];
    unproject(-1, a);
    unproject(1, b);
    RayProfile none;
    double t0 = 0, t1 = 1;
    for (int k = 0; k < 3; ++k) {
        const double d = b[k] - a[k];
        if (std::abs(d) < 1e-300) {
            if (a[k] < 0 || a[k] > dims[k] - 1) return none;
            continue;
        }
        double u0 = (0 - a[k]) / d, u1 = (dims[k] - 1 - a[k]) / d;
        if (u0 > u1) std::swap(u0, u1);
        t0 = std::max(t0, u0), t1 = std::min(t1, u1);
    }
    if (slab) { // the signed distance is linear in t: s(t) = s0 + t ds
        double s0 = slab->offset, ds = 0;
        for (int k = 0; k < 3; ++k)
            s0 += slab->normal[k] * a[k], ds += slab->normal[k] * (b[k] - a[k]);
        if (std::abs(ds) < 1e-300) {
            if (s0 < slab->lo || s0 > slab->hi) return none;
        } else {
            double u0 = (slab->lo - s0) / ds, u1 = (slab->hi - s0) / ds;
            if (u0 > u1) std::swap(u0, u1);
            t0 = std::max(t0, u0), t1 = std::min(t1, u1);
        }
    }
    if (t0 > t1) return none;
    RayProfile profile{INFINITY, 0.0, -INFINITY};
    const int n = samples + samples % 2; // composite Simpson: exact for the cubics of one polynomial
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
        const double t = t0 + (t1 - t0) * i / n;
        const double v = f(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]));
        profile.min = std::min(profile.min, v);
        profile.max = std::max(profile.max, v);
        sum += v * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
    }
    profile.mean = sum / (3.0 * n);
    return profile;
}

double cpuRayMax(const render::CameraMatrices& m, const std::array<int, 3>& dims, int width, int height,
                 int px, int py, const std::function<double(double, double, double)>& f, int samples) {
    return cpuRayProfile(m, dims, width, height, px, py, f, samples).max;
}

void saveForInspection(const render::FloatImage& image, const std::string& name) {
    float lo = INFINITY, hi = -INFINITY;
    for (float v : image.pixels)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!(lo <= hi)) lo = 0, hi = 1;
    std::filesystem::create_directories("/tmp/vots_render_tests");
    render::writePng("/tmp/vots_render_tests/" + name + ".png",
                     render::applyDisplay(image, render::windowForRange(lo, hi)));
}

double worstDifference(const render::FloatImage& image, const std::function<double(int, int)>& expect,
                       int* hits) {
    double worst = 0;
    *hits = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double want = expect(x, y);
            const float got = image.at(x, y);
            if (!std::isfinite(want)) {
                EXPECT_FALSE(std::isfinite(got)) << x << "," << y;
                continue;
            }
            ++*hits;
            worst = std::max(worst, std::abs(got - want));
        }
    return worst;
}

FittedVolume fitForImages(const std::string& path, float epsOfRange) {
    FittedVolume f;
    f.volume = fit::loadVolume(path);
    const auto range = f.volume.valueRange();
    fit::FitOptions options;
    options.eps = epsOfRange * (range[1] - range[0]);
    options.degree = 3;
    options.background = fit::defaultBackground(f.volume);
    // Samples-only certification lets a cubic overshoot between grid samples next to bone (docs/DESIGN.md
    // §3); a projection picks exactly those spikes, so the image tests certify the cell centres too.
    options.certify = fit::Certify::Cells;
    f.space = fit::fitVotSpace(f.volume, options).space;
    f.eps = options.eps;
    return f;
}

ImageComparison compareImages(const render::FloatImage& a, const render::FloatImage& b, double tolerance) {
    ImageComparison c;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const float x = a.pixels[i], y = b.pixels[i];
        if (x == y || (std::isnan(x) && std::isnan(y))) {
            ++c.bitIdentical;
            continue;
        }
        if (std::isfinite(x) != std::isfinite(y)) {
            ++c.finiteMismatch;
            continue;
        }
        const double d = std::abs(double(x) - y);
        c.worst = std::max(c.worst, d);
        if (d > tolerance) ++c.beyondTolerance;
    }
    return c;
}

} // namespace vots::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    vots::test::gContext = vots::render::EglContext::create(&vots::test::gContextError);
    if (!vots::test::gContext) std::cerr << "vots_render_tests: " << vots::test::gContextError << '\n';
    return RUN_ALL_TESTS();
}
