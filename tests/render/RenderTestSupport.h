// Shared helpers for renderer tests: one GL context per process, hand-built Vot-Spaces, CPU ray oracle.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/Camera.h"
#include "vots/render/EglContext.h"
#include "vots/render/Image.h"
#include "vots/render/Slab.h"

#include "SampleVolume.h" // sampleVolume(), shared with the other modules' tests

#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <optional>
#include <random>
#include <string>

namespace vots::test {

/// The process-wide context (created by main before any test); skips would hide bugs, so a missing
/// context fails every GL test with the EGL reason.
render::EglContext& glContext();

/// Polynomial of degree <= 3 in index coordinates, stored as Taylor coefficients around `centre`.
struct Polynomial {
    std::array<double, 3> centre{0, 0, 0};
    std::array<float, 20> c{};
    double operator()(double x, double y, double z) const;
};

/// Random polynomial of the given degree with coefficients scaled so values stay O(amplitude) over
/// a grid of side n.
Polynomial randomPolynomial(int degree, int n, double amplitude, std::uint32_t seed);

/// Exact cell Vots (docs/DESIGN.md §2): one per 2x2x2 cell, reproducing trilinear interpolation.
fit::VotSpace cellVotSpace(const fit::Volume& volume);

/// The polynomial split into boxes of `side` cells, each Vot expanded around its own box centre moved
/// by `offCentre` cells along every axis.
fit::VotSpace polynomialVotSpace(const Polynomial& p, const std::array<int, 3>& dims, int side,
                                 float offCentre = 0.f);

/// The oblique view of the polynomial tests: az 31, el 23, zoom 1.3, in the given projection.
render::Camera obliqueCamera(render::Projection projection);

/// Min, mean and max of f along a pixel's ray within the index box [0, dims-1] (and the slab, if given), by
/// dense sampling on the CPU (double; the mean by Simpson's rule, exact for a cubic). All -inf when the
/// ray misses.
struct RayProfile {
    double min = -INFINITY;
    double mean = -INFINITY;
    double max = -INFINITY;
};
RayProfile cpuRayProfile(const render::CameraMatrices& m, const std::array<int, 3>& dims, int width,
                         int height, int px, int py, const std::function<double(double, double, double)>& f,
                         int samples, const std::optional<render::SlabPlanes>& slab = std::nullopt);
/// Max of f along a pixel's ray within the index box [0, dims-1], by dense sampling on the CPU (double).
double cpuRayMax(const render::CameraMatrices& m, const std::array<int, 3>& dims, int width, int height,
                 int px, int py, const std::function<double(double, double, double)>& f, int samples);

/// The worst |image - expect(x, y)| over the pixels whose expected value is finite; a pixel whose expected
/// value is not (the ray misses) must be non-finite in the image too (a test failure otherwise). `hits`
/// gets the number of finite expected pixels.
double worstDifference(const render::FloatImage& image, const std::function<double(int, int)>& expect,
                       int* hits);

/// A real volume fitted for the image tests: cubic, the default background, certified at the cell
/// centres too (the images see between samples), eps the given fraction of the value range.
struct FittedVolume {
    fit::Volume volume;
    fit::VotSpace space;
    float eps = 0.f;
};
FittedVolume fitForImages(const std::string& path, float epsOfRange);

/// How two float images of one size differ, pixel by pixel.
struct ImageComparison {
    std::size_t finiteMismatch = 0; // background (non-finite) in one image only
    std::size_t beyondTolerance = 0;
    std::size_t bitIdentical = 0;
    double worst = 0; // the largest difference of pixels finite in both
};
ImageComparison compareImages(const render::FloatImage& a, const render::FloatImage& b, double tolerance);

/// Writes a PNG under /tmp/vots_render_tests/ for looking at (grey, full range of finite values).
void saveForInspection(const render::FloatImage& image, const std::string& name);

} // namespace vots::test
