// Beam bounds for early ray termination: every brick a ray can reach from a point of a brick is bounded.
#include "BrickAhead.h"

#include "vots/render/Camera.h"
#include "vots/render/CameraText.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace vots::render {
namespace {

constexpr int SHIFT = 2; // bricks of 4 cells keep the grid small and the beams many bricks long

BrickLayout testLayout() {
    BrickLayout layout;
    layout.cells = {37, 29, 22}; // partial bricks at the far ends
    layout.brickShift = SHIFT;
    for (int a = 0; a < 3; ++a)
        layout.bricks[a] = ((layout.cells[a] - 1) >> SHIFT) + 1;
    return layout;
}

std::size_t brickIndex(const BrickLayout& l, const std::array<double, 3>& p) {
    std::size_t index = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
        const int cell = std::clamp(static_cast<int>(std::floor(p[a])), 0, l.cells[a] - 1);
        index += stride * static_cast<std::size_t>(cell >> l.brickShift);
        stride *= static_cast<std::size_t>(l.bricks[a]);
    }
    return index;
}

// Follows rays of the family from random points of every brick in small steps and checks each brick
// met against the bound of the brick the ray started in.
void expectBeamsBounded(const RayFamily& rays, std::uint32_t seed) {
    const BrickLayout layout = testLayout();
    const std::size_t count = static_cast<std::size_t>(layout.bricks[0]) *
                              static_cast<std::size_t>(layout.bricks[1] * layout.bricks[2]);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> value(-100.f, 100.f);
    std::vector<float> brickMax(count);
    for (float& m : brickMax)
        m = value(rng);
    const std::vector<float> ahead = brickMaximaAhead(layout, brickMax, rays);
    ASSERT_EQ(ahead.size(), count);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t bounded = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        std::array<double, 3> p;
        for (int a = 0; a < 3; ++a)
            p[a] = unit(rng) * layout.cells[a];
        std::array<double, 3> d = rays.direction;
        if (!rays.parallel)
            for (int a = 0; a < 3; ++a)
                d[a] = p[a] - rays.eye[a];
        const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const float bound = ahead[brickIndex(layout, p)];
        EXPECT_GE(bound, brickMax[brickIndex(layout, p)]);
        if (std::isinf(bound)) continue;
        ++bounded;
        for (double t = 0.0;; t += 0.05) {
            std::array<double, 3> q;
            bool inside = true;
            for (int a = 0; a < 3; ++a) {
                q[a] = p[a] + t * d[a] / length;
                inside = inside && q[a] >= 0.0 && q[a] < layout.cells[a];
            }
            if (!inside) break;
            ASSERT_LE(brickMax[brickIndex(layout, q)], bound) << "trial " << trial << " t " << t;
        }
    }
    EXPECT_GT(bounded, 2000u); // the bounds are not all +inf
}

TEST(BrickAhead, ParallelRaysNeverMeetABrickAboveTheBound) {
    expectBeamsBounded({true, {0.0, 1.0, 0.0}, {}}, 1u);   // along an axis
    expectBeamsBounded({true, {-0.6, 0.3, 0.74}, {}}, 2u); // oblique
    expectBeamsBounded({true, {1.0, -1.0, 1.0}, {}}, 3u);  // diagonal: ties for the dominant axis
}

TEST(BrickAhead, PerspectiveRaysNeverMeetABrickAboveTheBound) {
    expectBeamsBounded({false, {}, {18.0, -40.0, 11.0}}, 4u);
    expectBeamsBounded({false, {}, {80.0, 70.0, -30.0}}, 5u);
}

// Tight enough to stop rays: with brickMax growing along x and rays along z, a brick's bound comes from
// its own column and at most two beside it (the margin reaches the next column, the tubes one more), not
// from the whole grid.
TEST(BrickAhead, ABoundComesFromTheBeamNotTheWholeGrid) {
    const BrickLayout layout = testLayout();
    std::vector<float> brickMax;
    for (int bz = 0; bz < layout.bricks[2]; ++bz)
        for (int by = 0; by < layout.bricks[1]; ++by)
            for (int bx = 0; bx < layout.bricks[0]; ++bx)
                brickMax.push_back(static_cast<float>(bx));
    for (double dz : {1.0, -1.0}) {
        const std::vector<float> ahead = brickMaximaAhead(layout, brickMax, {true, {0.0, 0.0, dz}, {}});
        for (std::size_t i = 0; i < ahead.size(); ++i) {
            const float own = brickMax[i];
            EXPECT_GE(ahead[i], own) << "brick " << i;
            EXPECT_LE(ahead[i], std::min(own + 2.f, float(layout.bricks[0] - 1))) << "brick " << i;
        }
    }
}

TEST(BrickAhead, AnEyeInsideTheGridLeavesNearbyBricksUnbounded) {
    const BrickLayout layout = testLayout();
    const std::vector<float> brickMax(
        static_cast<std::size_t>(layout.bricks[0] * layout.bricks[1] * layout.bricks[2]), 1.f);
    const std::vector<float> ahead = brickMaximaAhead(layout, brickMax, {false, {}, {18.0, 14.0, 11.0}});
    EXPECT_TRUE(std::isinf(ahead[brickIndex(layout, {18.0, 14.0, 11.0})]));
}

TEST(BrickAhead, RayFamilyComesFromTheCamera) {
    SceneBounds bounds;
    bounds.hi = {40.0, 30.0, 20.0};
    const CameraMatrices ortho = computeCameraMatrices(parseCamera("az=30,el=20,proj=ortho"), bounds, 64, 64);
    const RayFamily parallel = rayFamilyOf(ortho.clipToIndex);
    ASSERT_TRUE(parallel.parallel);
    const CameraMatrices persp = computeCameraMatrices(parseCamera("az=30,el=20,proj=persp"), bounds, 64, 64);
    const RayFamily central = rayFamilyOf(persp.clipToIndex);
    ASSERT_FALSE(central.parallel);
    // Every pixel ray (near point -> far point) runs along the family: parallel to the direction, or
    // on the line through the eye.
    for (const auto& [m, family] : {std::pair{ortho, parallel}, std::pair{persp, central}})
        for (double nx : {-0.9, 0.0, 0.7})
            for (double ny : {-0.5, 0.8}) {
                auto unproject = [&](double z) {
                    std::array<double, 4> c{nx, ny, z, 1.0}, out{};
                    for (int r = 0; r < 4; ++r)
                        for (int k = 0; k < 4; ++k)
                            out[r] += m.clipToIndex[4 * k + r] * c[k];
                    return std::array<double, 3>{out[0] / out[3], out[1] / out[3], out[2] / out[3]};
                };
                const auto a = unproject(-1.0), b = unproject(1.0);
                std::array<double, 3> ray{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
                std::array<double, 3> expected = family.direction;
                if (!family.parallel)
                    for (int k = 0; k < 3; ++k)
                        expected[k] = a[k] - family.eye[k];
                const double dot = ray[0] * expected[0] + ray[1] * expected[1] + ray[2] * expected[2];
                const double norms =
                    std::hypot(ray[0], ray[1], ray[2]) * std::hypot(expected[0], expected[1], expected[2]);
                EXPECT_NEAR(dot / norms, 1.0, 1e-9); // same direction, not opposite
            }
}

} // namespace
} // namespace vots::render
