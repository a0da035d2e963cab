// Places the slabs of a sweep along the view and each image in patient space, from the camera's own rays.
#include "vots/render/SlabSweep.h"

#include "vots/fit/Error.h"

#include "NumberText.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vots::render {
namespace {

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 minus(const Vec3& a, const Vec3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 scaled(const Vec3& a, double s) {
    return {a[0] * s, a[1] * s, a[2] * s};
}

/// The pixel-centre rays of one camera, in world (patient) coordinates.
class PixelRays {
public:
    PixelRays(const Camera& camera, const SceneBounds& bounds, int width, int height)
        : mBounds(bounds), mWidth(width), mHeight(height),
          mMatrices(computeCameraMatrices(camera, bounds, width, height)) {
        for (int c = 0; c < 3; ++c)
            mCentre[c] = 0.5 * (bounds.lo[c] + bounds.hi[c]);
        const auto [near, far] = ends(0.0, 0.0);
        const Vec3 along = minus(far, near);
        mForward = scaled(along, 1.0 / std::sqrt(dot(along, along)));
    }
    const Vec3& forward() const { return mForward; }
    const Vec3& centre() const { return mCentre; }

    /// Where the ray through pixel (x, y) (y = 0 the top row) meets the plane `offset` mm from the centre
    /// along the view.
    Vec3 onPlane(double x, double y, double offset) const {
        const auto [near, far] = ends((x + 0.5) / mWidth * 2.0 - 1.0, 1.0 - (y + 0.5) / mHeight * 2.0);
        const Vec3 along = minus(far, near);
        const double t = (offset - dot(mForward, minus(near, mCentre))) / dot(mForward, along);
        return {near[0] + t * along[0], near[1] + t * along[1], near[2] + t * along[2]};
    }

private:
    /// The ray's points on the near and far planes, as the shaders rebuild them (ray_common.glsl).
    std::pair<Vec3, Vec3> ends(double ndcX, double ndcY) const {
        return {world(ndcX, ndcY, -1.0), world(ndcX, ndcY, 1.0)};
    }
    Vec3 world(double ndcX, double ndcY, double ndcZ) const {
        const auto& m = mMatrices.clipToIndex; // column-major
        const double in[4] = {ndcX, ndcY, ndcZ, 1.0};
        double index[4] = {0, 0, 0, 0};
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col)
                index[row] += m[static_cast<std::size_t>(col * 4 + row)] * in[col];
        Vec3 w = mBounds.origin;
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c)
                w[c] += mBounds.axes[a][c] * mBounds.spacing[a] * index[a] / index[3];
        return w;
    }

    SceneBounds mBounds;
    int mWidth;
    int mHeight;
    CameraMatrices mMatrices;
    Vec3 mCentre{};
    Vec3 mForward{};
};

/// [lo, hi] of the grid's corners along `forward`, in mm from the centre.
std::array<double, 2> extentAlong(const Vec3& forward, const Vec3& centre, const SceneBounds& bounds) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int corner = 0; corner < 8; ++corner) {
        Vec3 w = bounds.origin;
        for (int a = 0; a < 3; ++a) {
            const double index = (corner >> a) & 1 ? bounds.dims[a] - 1 : 0;
            for (int c = 0; c < 3; ++c)
                w[c] += bounds.axes[a][c] * bounds.spacing[a] * index;
        }
        const double d = dot(forward, minus(w, centre));
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    return {lo, hi};
}

std::string millimetres(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

} // namespace

SlabSweepSpacing parseSlabSweep(std::string_view text) {
    const auto pair = detail::parseFinitePair(text);
    if (!pair || !((*pair)[0] > 0.0) || !((*pair)[1] > 0.0))
        throw fit::InputError("--slab-sweep '" + std::string(text.substr(0, 64)) +
                              "' is not THICKNESS,STEP in mm (two finite numbers, both > 0)");
    return {(*pair)[0], (*pair)[1]};
}

SlabSweepPlan planSlabSweep(const SlabSweepSpacing& spacing, const Camera& camera, const SceneBounds& bounds,
                            int width, int height) {
    if (camera.projection != Projection::Orthographic)
        throw fit::InputError("--slab-sweep needs an orthographic camera: a slab of a perspective view has "
                              "no single image plane");
    const PixelRays rays(camera, bounds, width, height);
    const auto [lo, hi] = extentAlong(rays.forward(), rays.centre(), bounds);
    // A whisker of tolerance, so that an extent that is a whole number of steps gets no extra slab.
    const double steps = std::ceil((hi - lo - spacing.thicknessMm) / spacing.stepMm - 1e-9);
    const double count = 1.0 + std::max(steps, 0.0);
    if (count > MAX_SWEEP_SLABS)
        throw fit::InputError("--slab-sweep " + millimetres(spacing.thicknessMm) + "," +
                              millimetres(spacing.stepMm) + " gives " + millimetres(count) +
                              " slabs through this volume (at most " + std::to_string(MAX_SWEEP_SLABS) + ")");
    SlabSweepPlan plan;
    const Vec3 first = rays.onPlane(0, 0, 0.0);
    const Vec3 right = minus(rays.onPlane(1, 0, 0.0), first);
    const Vec3 down = minus(rays.onPlane(0, 1, 0.0), first);
    plan.plane.pixelSpacingMm = std::sqrt(dot(right, right));
    plan.plane.rowDirection = scaled(right, 1.0 / plan.plane.pixelSpacingMm);
    plan.plane.columnDirection = scaled(down, 1.0 / std::sqrt(dot(down, down)));
    plan.plane.normal = rays.forward();
    const double run = spacing.thicknessMm + (count - 1.0) * spacing.stepMm;
    const double firstMiddle = 0.5 * (lo + hi) - 0.5 * run + 0.5 * spacing.thicknessMm;
    for (int k = 0; k < static_cast<int>(count); ++k) {
        SweepSlab s;
        s.slab = Slab{firstMiddle + k * spacing.stepMm, spacing.thicknessMm};
        s.firstPixelCentre = rays.onPlane(0, 0, s.slab.offsetMm);
        plan.slabs.push_back(s);
    }
    return plan;
}

FrameRequest sweepFrame(const FrameRequest& first, const SweepSlab& slab) {
    FrameRequest frame = first;
    frame.slab = slab.slab;
    return frame;
}

std::string_view sweepPlaneName(const std::array<double, 3>& normal) {
    constexpr double TOLERANCE = 1e-6;
    constexpr std::string_view NAMES[3] = {"sagittal", "coronal", "axial"};
    for (int a = 0; a < 3; ++a)
        if (std::abs(std::abs(normal[a]) - 1.0) < TOLERANCE) return NAMES[a];
    return "oblique";
}

std::string sweepDescription(RenderMode mode, const SlabSweepSpacing& spacing,
                             const std::array<double, 3>& normal) {
    const std::string name = mode == RenderMode::Mip     ? "MIP"
                             : mode == RenderMode::MinIp ? "MinIP"
                             : mode == RenderMode::Aip   ? "AIP"
                                                         : std::string(renderModeName(mode));
    return name + " " + millimetres(spacing.thicknessMm) + " mm / " + millimetres(spacing.stepMm) + " mm " +
           std::string(sweepPlaneName(normal));
}

} // namespace vots::render
