// Beam bounds: the bricks a ray may visit after leaving a point of a brick, slab by slab.
#include "BrickAhead.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vots::render {

namespace {

constexpr double MARGIN = 0.5; // cells by which a beam is widened: far above the walk's float rounding

// Column-major 4x4 matrix (GL layout) times (x, y, z, w).
std::array<double, 4> transform(const std::array<double, 16>& m, const std::array<double, 4>& v) {
    std::array<double, 4> out{};
    for (int r = 0; r < 4; ++r)
        out[r] = m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3];
    return out;
}

int dominantAxis(const std::array<double, 3>& v) {
    int a = 0;
    for (int i = 1; i < 3; ++i)
        if (std::abs(v[i]) > std::abs(v[a])) a = i;
    return a;
}

} // namespace

RayFamily rayFamilyOf(const std::array<double, 16>& clipToIndex) {
    // Clip (0, 0, 1, 0) is the eye of a perspective projection and the view direction of an
    // orthographic one (w = 0 there): both are where every ray meets.
    const std::array<double, 4> v = transform(clipToIndex, {0, 0, 1, 0});
    RayFamily rays;
    const double scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    if (std::abs(v[3]) <= 1e-12 * scale) {
        // Rays run from near (clip z = -1) to far (z = +1), so the direction is clip +z mapped.
        rays.parallel = true;
        rays.direction = {v[0], v[1], v[2]};
    } else {
        rays.parallel = false;
        rays.eye = {v[0] / v[3], v[1] / v[3], v[2] / v[3]};
    }
    return rays;
}

std::vector<float> brickMaximaAhead(const BrickLayout& layout, const std::vector<float>& brickMax,
                                    const RayFamily& rays) {
    const auto& nb = layout.bricks;
    const int side = 1 << layout.brickShift;
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> ahead(brickMax.size(), inf);
    auto brickAt = [&](int x, int y, int z) {
        return brickMax[static_cast<std::size_t>(x) +
                        static_cast<std::size_t>(nb[0]) *
                            (static_cast<std::size_t>(y) +
                             static_cast<std::size_t>(nb[1]) * static_cast<std::size_t>(z))];
    };
    for (int bz = 0; bz < nb[2]; ++bz)
        for (int by = 0; by < nb[1]; ++by)
            for (int bx = 0; bx < nb[0]; ++bx) {
                const int b[3] = {bx, by, bz};
                double lo[3], hi[3], centre[3];
                for (int a = 0; a < 3; ++a) {
                    lo[a] = b[a] * side;
                    hi[a] = std::min((b[a] + 1) * side, layout.cells[a]);
                    centre[a] = 0.5 * (lo[a] + hi[a]);
                }
                // The beam's dominant axis and the way it runs along it.
                std::array<double, 3> heading = rays.direction;
                if (!rays.parallel)
                    for (int a = 0; a < 3; ++a)
                        heading[a] = centre[a] - rays.eye[a];
                const int axis = dominantAxis(heading);
                if (heading[axis] == 0.0) continue; // no direction: keep +inf
                const int step = heading[axis] > 0 ? 1 : -1;
                // A perspective beam is bounded only when the eye lies clearly before B along the axis.
                if (!rays.parallel &&
                    (step > 0 ? rays.eye[axis] > lo[axis] - side : rays.eye[axis] < hi[axis] + side))
                    continue;
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                float best = -inf;
                for (int layer = b[axis]; layer >= 0 && layer < nb[axis]; layer += step) {
                    const double s0 = layer * side, s1 = std::min((layer + 1) * side, layout.cells[axis]);
                    double range[2][2] = {{INFINITY, -INFINITY}, {INFINITY, -INFINITY}}; // [u|v][min|max]
                    for (int corner = 0; corner < 8; ++corner) {
                        const double p[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                                             corner & 4 ? hi[2] : lo[2]};
                        for (double s : {s0, s1}) {
                            // Where the line through p of the family crosses the plane x_axis = s.
                            double q[2];
                            if (rays.parallel) {
                                const double t = (s - p[axis]) / rays.direction[axis];
                                q[0] = p[u] + t * rays.direction[u];
                                q[1] = p[v] + t * rays.direction[v];
                            } else {
                                const double t = (s - rays.eye[axis]) / (p[axis] - rays.eye[axis]);
                                q[0] = rays.eye[u] + t * (p[u] - rays.eye[u]);
                                q[1] = rays.eye[v] + t * (p[v] - rays.eye[v]);
                            }
                            for (int k = 0; k < 2; ++k) {
                                range[k][0] = std::min(range[k][0], q[k]);
                                range[k][1] = std::max(range[k][1], q[k]);
                            }
                        }
                    }
                    int first[2], last[2];
                    const int perpendicular[2] = {u, v};
                    bool outside = false; // the beam misses the grid in this slab
                    for (int k = 0; k < 2; ++k) {
                        const int a = perpendicular[k];
                        const double from = std::max(range[k][0] - MARGIN, 0.0);
                        const double to = std::min(range[k][1] + MARGIN, double(layout.cells[a]) - 1e-9);
                        if (!(from <= to)) {
                            outside = true;
                            break;
                        }
                        first[k] = static_cast<int>(from) >> layout.brickShift;
                        last[k] = static_cast<int>(to) >> layout.brickShift;
                    }
                    if (outside) continue;
                    for (int i = first[0]; i <= last[0]; ++i)
                        for (int j = first[1]; j <= last[1]; ++j) {
                            int at[3];
                            at[axis] = layer;
                            at[u] = i;
                            at[v] = j;
                            best = std::max(best, brickAt(at[0], at[1], at[2]));
                        }
                }
                ahead[static_cast<std::size_t>(bx) +
                      static_cast<std::size_t>(nb[0]) *
                          (static_cast<std::size_t>(by) +
                           static_cast<std::size_t>(nb[1]) * static_cast<std::size_t>(bz))] = best;
            }
    return ahead;
}

} // namespace vots::render
