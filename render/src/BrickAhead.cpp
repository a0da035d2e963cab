// Beam bounds: the bricks a ray may visit after leaving a point of a brick, by tubes of rays far to near.
#include "BrickAhead.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vots::render {

namespace {

constexpr double MARGIN = 0.5; // cells by which a footprint is widened: far above the walk's float rounding
constexpr int MAX_TUBES_PER_SIDE = 512; // caps the work of a view whose rays spread very wide

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

// The rays of a family that advance along `axis` in the direction `step`, labelled by two numbers that
// stay the same along each ray (its "tube coordinates" tau): for parallel rays the ray's offset
// p_u - r_u p_a in the plane p_a = 0, for rays from an eye its slopes (p_u - e_u) / (p_a - e_a). Both
// make p_u bilinear in (tau_u, p_a), so a box of tau over a slab [s0, s1] reaches its extremes at corners.
struct TubeFrame {
    RayFamily rays;
    int axis = 0, u = 1, v = 2;
    double slope[2] = {0.0, 0.0}; // parallel: d_u / d_a, d_v / d_a

    std::array<double, 2> tau(const double p[3]) const {
        if (rays.parallel) return {p[u] - slope[0] * p[axis], p[v] - slope[1] * p[axis]};
        const double along = p[axis] - rays.eye[axis];
        return {(p[u] - rays.eye[u]) / along, (p[v] - rays.eye[v]) / along};
    }
    // The label along perpendicular k of the ray through position q on it where it crosses p_a = s.
    double tauAt(int k, double q, double s) const {
        if (rays.parallel) return q - slope[k] * s;
        return (q - rays.eye[k == 0 ? u : v]) / (s - rays.eye[axis]);
    }
    // The position along perpendicular k (0: u, 1: v) of the ray labelled `t` where it crosses p_a = s.
    double at(int k, double t, double s) const {
        if (rays.parallel) return t + slope[k] * s;
        return rays.eye[k == 0 ? u : v] + t * (s - rays.eye[axis]);
    }
};

struct Box3 {
    double lo[3], hi[3];
};

class AheadBuilder {
public:
    AheadBuilder(const BrickLayout& layout, const std::vector<float>& brickMax, std::vector<float>& ahead)
        : mLayout(layout), mBrickMax(brickMax), mAhead(ahead), mSide(1 << layout.brickShift) {}

    std::size_t index(int x, int y, int z) const {
        const auto& nb = mLayout.bricks;
        return static_cast<std::size_t>(x) +
               static_cast<std::size_t>(nb[0]) *
                   (static_cast<std::size_t>(y) +
                    static_cast<std::size_t>(nb[1]) * static_cast<std::size_t>(z));
    }
    Box3 brickBox(const int b[3]) const {
        Box3 box;
        for (int a = 0; a < 3; ++a) {
            box.lo[a] = b[a] * mSide;
            box.hi[a] = std::min((b[a] + 1) * mSide, mLayout.cells[a]);
        }
        return box;
    }
    // The smallest and largest tau over the brick's corners, per perpendicular.
    void tauRange(const TubeFrame& frame, const Box3& box, double lo[2], double hi[2]) const {
        lo[0] = lo[1] = INFINITY;
        hi[0] = hi[1] = -INFINITY;
        for (int corner = 0; corner < 8; ++corner) {
            const double p[3] = {corner & 1 ? box.hi[0] : box.lo[0], corner & 2 ? box.hi[1] : box.lo[1],
                                 corner & 4 ? box.hi[2] : box.lo[2]};
            const auto t = frame.tau(p);
            for (int k = 0; k < 2; ++k) {
                lo[k] = std::min(lo[k], t[k]);
                hi[k] = std::max(hi[k], t[k]);
            }
        }
    }

    // Fills mAhead for the bricks for which `member` holds; every one of them must lie beyond the eye
    // (if any) by at least a brick along frame.axis, in the direction `step`.
    template <typename Member> void run(const TubeFrame& frame, int step, Member&& member) {
        const int a = frame.axis, u = frame.u, v = frame.v;
        const auto& nb = mLayout.bricks;
        // The members' layers and their tau range: every ray that starts in a member keeps its tau.
        int nearest = -1;
        double tauLo[2] = {INFINITY, INFINITY}, tauHi[2] = {-INFINITY, -INFINITY};
        if (frame.rays.parallel) { // every brick is a member; tau is linear, so the grid's corners do
            nearest = step > 0 ? 0 : nb[a] - 1;
            tauRange(frame,
                     Box3{{0.0, 0.0, 0.0},
                          {double(mLayout.cells[0]), double(mLayout.cells[1]), double(mLayout.cells[2])}},
                     tauLo, tauHi);
        } else
            for (int bz = 0; bz < nb[2]; ++bz)
                for (int by = 0; by < nb[1]; ++by)
                    for (int bx = 0; bx < nb[0]; ++bx) {
                        const int b[3] = {bx, by, bz};
                        if (!member(b)) continue;
                        if (nearest < 0 || (step > 0 ? b[a] < nearest : b[a] > nearest)) nearest = b[a];
                        double lo[2], hi[2];
                        tauRange(frame, brickBox(b), lo, hi);
                        for (int k = 0; k < 2; ++k) {
                            tauLo[k] = std::min(tauLo[k], lo[k]);
                            tauHi[k] = std::max(tauHi[k], hi[k]);
                        }
                    }
        if (nearest < 0) return;
        const int farthest = step > 0 ? nb[a] - 1 : 0;
        // Tubes about a brick wide where they leave the grid: the bound is the beam's, widened by a tube.
        double width[2];
        int tubes[2];
        const double farPlane = step > 0 ? mLayout.cells[a] : 0.0;
        const double reach = frame.rays.parallel ? 1.0 : std::abs(farPlane - frame.rays.eye[a]);
        for (int k = 0; k < 2; ++k) {
            const double span = std::max(tauHi[k] - tauLo[k], 1e-12);
            width[k] = std::max(mSide / reach, span / MAX_TUBES_PER_SIDE);
            tubes[k] = std::max(1, static_cast<int>(std::ceil(span / width[k])));
        }
        const float inf = std::numeric_limits<float>::infinity();
        std::vector<float> tubeMax(static_cast<std::size_t>(tubes[0]) * static_cast<std::size_t>(tubes[1]),
                                   -inf);
        const int perpendicular[2] = {u, v};
        for (int layer = farthest;; layer -= step) {
            const double s0 = layer * mSide, s1 = std::min((layer + 1) * mSide, mLayout.cells[a]);
            // Each tube's running max gains the bricks its rays cross in this slab; only the tubes whose
            // rays can meet the grid in it need looking at.
            int tubeFrom[2], tubeTo[2];
            for (int k = 0; k < 2; ++k) {
                double lo = INFINITY, hi = -INFINITY;
                for (double q : {-MARGIN, mLayout.cells[perpendicular[k]] + MARGIN})
                    for (double s : {s0, s1}) {
                        const double t = frame.tauAt(k, q, s);
                        lo = std::min(lo, t);
                        hi = std::max(hi, t);
                    }
                tubeFrom[k] =
                    std::clamp(static_cast<int>(std::floor((lo - tauLo[k]) / width[k])), 0, tubes[k] - 1);
                tubeTo[k] =
                    std::clamp(static_cast<int>(std::floor((hi - tauLo[k]) / width[k])), 0, tubes[k] - 1);
            }
            for (int i = tubeFrom[0]; i <= tubeTo[0]; ++i)
                for (int j = tubeFrom[1]; j <= tubeTo[1]; ++j) {
                    const double t[2][2] = {{tauLo[0] + i * width[0], tauLo[0] + (i + 1) * width[0]},
                                            {tauLo[1] + j * width[1], tauLo[1] + (j + 1) * width[1]}};
                    int first[2], last[2];
                    bool outside = false;
                    for (int k = 0; k < 2 && !outside; ++k) {
                        double lo = INFINITY, hi = -INFINITY;
                        for (double tk : t[k])
                            for (double s : {s0, s1}) {
                                const double q = frame.at(k, tk, s);
                                lo = std::min(lo, q);
                                hi = std::max(hi, q);
                            }
                        const double from = std::max(lo - MARGIN, 0.0);
                        const double to =
                            std::min(hi + MARGIN, double(mLayout.cells[perpendicular[k]]) - 1e-9);
                        outside = !(from <= to);
                        first[k] = outside ? 0 : static_cast<int>(from) >> mLayout.brickShift;
                        last[k] = outside ? -1 : static_cast<int>(to) >> mLayout.brickShift;
                    }
                    if (outside) continue;
                    float& best = tubeMax[static_cast<std::size_t>(i) * static_cast<std::size_t>(tubes[1]) +
                                          static_cast<std::size_t>(j)];
                    for (int bi = first[0]; bi <= last[0]; ++bi)
                        for (int bj = first[1]; bj <= last[1]; ++bj) {
                            int at[3];
                            at[a] = layer;
                            at[u] = bi;
                            at[v] = bj;
                            best = std::max(best, mBrickMax[index(at[0], at[1], at[2])]);
                        }
                }
            // A member of this layer is bounded by the tubes its rays run in: they hold this slab and all
            // beyond it.
            for (int bi = 0; bi < nb[u]; ++bi)
                for (int bj = 0; bj < nb[v]; ++bj) {
                    int b[3];
                    b[a] = layer;
                    b[u] = bi;
                    b[v] = bj;
                    if (!member(b)) continue;
                    double lo[2], hi[2];
                    tauRange(frame, brickBox(b), lo, hi);
                    int from[2], to[2];
                    for (int k = 0; k < 2; ++k) {
                        from[k] = std::clamp(static_cast<int>(std::floor((lo[k] - tauLo[k]) / width[k])), 0,
                                             tubes[k] - 1);
                        to[k] = std::clamp(static_cast<int>(std::floor((hi[k] - tauLo[k]) / width[k])), 0,
                                           tubes[k] - 1);
                    }
                    float bound = -inf;
                    for (int i = from[0]; i <= to[0]; ++i)
                        for (int j = from[1]; j <= to[1]; ++j)
                            bound = std::max(
                                bound,
                                tubeMax[static_cast<std::size_t>(i) * static_cast<std::size_t>(tubes[1]) +
                                        static_cast<std::size_t>(j)]);
                    // The brick itself, in case rounding put its whole tau range outside the tubes' grid.
                    mAhead[index(b[0], b[1], b[2])] = std::max(bound, mBrickMax[index(b[0], b[1], b[2])]);
                }
            if (layer == nearest) break;
        }
    }

private:
    const BrickLayout& mLayout;
    const std::vector<float>& mBrickMax;
    std::vector<float>& mAhead;
    int mSide;
};

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
    std::vector<float> ahead(brickMax.size(), std::numeric_limits<float>::infinity());
    AheadBuilder builder(layout, brickMax, ahead);
    const int side = 1 << layout.brickShift;
    auto frameFor = [&](int axis) {
        TubeFrame frame;
        frame.rays = rays;
        frame.axis = axis;
        frame.u = (axis + 1) % 3;
        frame.v = (axis + 2) % 3;
        if (rays.parallel) {
            frame.slope[0] = rays.direction[frame.u] / rays.direction[axis];
            frame.slope[1] = rays.direction[frame.v] / rays.direction[axis];
        }
        return frame;
    };
    if (rays.parallel) {
        const int axis = dominantAxis(rays.direction);
        if (rays.direction[axis] == 0.0) return ahead; // no direction: every bound stays +inf
        builder.run(frameFor(axis), rays.direction[axis] > 0 ? 1 : -1, [](const int*) { return true; });
        return ahead;
    }
    // Rays from an eye: each brick goes with the dominant axis of the eye-to-centre heading, and is
    // bounded only when the eye lies clearly before it along that axis (else its beam spreads too wide).
    // Its group (axis, direction) is worked out once: 2 * axis + (step < 0), or -1 for unbounded.
    const auto& nb = layout.bricks;
    std::vector<signed char> group(brickMax.size(), -1);
    for (int bz = 0; bz < nb[2]; ++bz)
        for (int by = 0; by < nb[1]; ++by)
            for (int bx = 0; bx < nb[0]; ++bx) {
                const int b[3] = {bx, by, bz};
                const Box3 box = builder.brickBox(b);
                std::array<double, 3> heading;
                for (int a = 0; a < 3; ++a)
                    heading[a] = 0.5 * (box.lo[a] + box.hi[a]) - rays.eye[a];
                const int axis = dominantAxis(heading);
                const bool clear = heading[axis] > 0 ? rays.eye[axis] <= box.lo[axis] - side
                                                     : rays.eye[axis] >= box.hi[axis] + side;
                if (clear)
                    group[builder.index(bx, by, bz)] =
                        static_cast<signed char>(2 * axis + (heading[axis] < 0));
            }
    for (int axis = 0; axis < 3; ++axis)
        for (int step : {1, -1}) {
            const signed char wanted = static_cast<signed char>(2 * axis + (step < 0));
            builder.run(frameFor(axis), step,
                        [&](const int* b) { return group[builder.index(b[0], b[1], b[2])] == wanted; });
        }
    return ahead;
}

} // namespace vots::render
