// Slab sweeps: how many slabs a volume gets and where, and that each image's patient-space geometry is where
// the renderer draws it (the average of a linear field over a slab is its value on the middle plane).
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/SlabSweep.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vots;
using namespace vots::render;

namespace {

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// A grid stored as left-posterior... rotated about z by 90 degrees and flipped in y: x runs posterior,
/// y runs to the patient's right, z superior; anisotropic, off the origin.
fit::Volume rotatedGrid(const std::function<double(const Vec3&)>& field) {
    fit::Volume v = test::sampleVolume({21, 17, 31}, [](int, int, int) { return 0.0; }, {1.2, 0.9, 0.7});
    v.patientAxes = {{{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}}};
    v.orientationKnown = true;
    v.origin = {14.0, -30.0, 55.0};
    for (int z = 0; z < v.dims[2]; ++z)
        for (int y = 0; y < v.dims[1]; ++y)
            for (int x = 0; x < v.dims[0]; ++x) {
                Vec3 w = v.origin;
                const int index[3] = {x, y, z};
                for (int a = 0; a < 3; ++a)
                    for (int c = 0; c < 3; ++c)
                        w[c] += v.patientAxes[a][c] * v.spacing[a] * index[a];
                v.values[v.indexOf(x, y, z)] = static_cast<float>(field(w));
            }
    return v;
}

/// Whether the patient-space point lies inside the grid box by at least `margin` mm.
bool insideGrid(const fit::Volume& v, const Vec3& w, double margin) {
    for (int a = 0; a < 3; ++a) {
        double along = 0.0;
        for (int c = 0; c < 3; ++c)
            along += v.patientAxes[a][c] * (w[c] - v.origin[c]);
        if (along < margin || along > v.spacing[a] * (v.dims[a] - 1) - margin) return false;
    }
    return true;
}

TEST(SlabSweep, CountsAndCentresTheSlabsOnTheVolume) {
    // Identity axes, z extent 20 mm: the superior view looks down z.
    const fit::Volume v = test::sampleVolume({11, 9, 41}, [](int, int, int) { return 0.0; }, {1.0, 1.0, 0.5});
    const SceneBounds bounds = sceneBounds(v);
    const Camera superior = cameraForView(ViewPreset::Superior);
    const auto middles = [&](double thickness, double step) {
        std::vector<double> out;
        for (const SweepSlab& s : planSlabSweep({thickness, step}, superior, bounds, 32, 32).slabs) {
            EXPECT_EQ(s.slab.thicknessMm, thickness);
            out.push_back(s.slab.offsetMm);
        }
        return out;
    };
    const auto expectNear = [](const std::vector<double>& got, const std::vector<double>& want) {
        ASSERT_EQ(got.size(), want.size());
        for (std::size_t k = 0; k < got.size(); ++k)
            EXPECT_NEAR(got[k], want[k], 1e-9) << k;
    };
    expectNear(middles(10, 5), {-5, 0, 5}); // 1 + ceil((20 - 10) / 5): exactly covers, no extra slab
    expectNear(middles(4, 3), {-9, -6, -3, 0, 3, 6, 9}); // 1 + ceil(16 / 3) = 7, the run of 22 mm centred
    expectNear(middles(30, 5), {0});                     // thicker than the volume: one slab
    expectNear(middles(20, 1), {0});
    EXPECT_EQ(middles(1, 1).size(), 20u);
    EXPECT_THROW(planSlabSweep({0.001, 0.001}, superior, bounds, 32, 32), fit::InputError);
    Camera perspective = superior;
    perspective.projection = Projection::Perspective;
    EXPECT_THROW(planSlabSweep({10, 5}, perspective, bounds, 32, 32), fit::InputError);
}

TEST(SlabSweep, ParsesThicknessAndStep) {
    const SlabSweepSpacing s = parseSlabSweep("10,5");
    EXPECT_EQ(s.thicknessMm, 10.0);
    EXPECT_EQ(s.stepMm, 5.0);
    for (const char* bad : {"", "10", "0,5", "10,0", "-1,5", "10,-5", "nan,5", "10,inf", "10;5", "10,5,1"})
        EXPECT_THROW(parseSlabSweep(bad), fit::InputError) << bad;
}

TEST(SlabSweep, NamesTheModeSlabAndPlane) {
    EXPECT_EQ(sweepDescription(RenderMode::Mip, {10, 5}, {0, 0, 1}), "MIP 10 mm / 5 mm axial");
    EXPECT_EQ(sweepDescription(RenderMode::MinIp, {2.5, 1.25}, {0, -1, 0}), "MinIP 2.5 mm / 1.25 mm coronal");
    EXPECT_EQ(sweepDescription(RenderMode::Aip, {10, 5}, {1, 0, 0}), "AIP 10 mm / 5 mm sagittal");
    EXPECT_EQ(sweepPlaneName({0.6, 0.8, 0}), "oblique");
}

// For each view, every slab's image: where the slab lies wholly inside the grid, the grid renderer's aip
// of a linear field is the field at the pixel's patient position on the middle plane.
TEST(SlabSweep, ImagesLieWhereTheRendererDrawsThem) {
    test::glContext();
    const auto field = [](const Vec3& w) { return 3.0 * w[0] - 2.0 * w[1] + 5.0 * w[2] + 100.0; };
    const fit::Volume v = rotatedGrid(field);
    GridRenderer grid;
    grid.upload(v);
    Camera oblique;
    oblique.azimuthDeg = 30;
    oblique.elevationDeg = 20;
    oblique.zoom = 1.4;
    oblique.panX = 0.1;
    constexpr int W = 40, H = 30;
    const SlabSweepSpacing spacing{4.0, 3.0};
    for (const Camera& camera :
         {cameraForView(ViewPreset::Inferior), cameraForView(ViewPreset::Superior),
          cameraForView(ViewPreset::Left), cameraForView(ViewPreset::Anterior), oblique}) {
        const SlabSweepPlan plan = planSlabSweep(spacing, camera, grid.bounds(), W, H);
        const SweepImagePlane& p = plan.plane;
        EXPECT_NEAR(dot(p.rowDirection, p.columnDirection), 0.0, 1e-12);
        const Vec3 cross{p.rowDirection[1] * p.columnDirection[2] - p.rowDirection[2] * p.columnDirection[1],
                         p.rowDirection[2] * p.columnDirection[0] - p.rowDirection[0] * p.columnDirection[2],
                         p.rowDirection[0] * p.columnDirection[1] - p.rowDirection[1] * p.columnDirection[0]};
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(cross[c], p.normal[c], 1e-12);
        int checked = 0;
        for (std::size_t k = 0; k < plan.slabs.size(); ++k) {
            const SweepSlab& slab = plan.slabs[k];
            if (k > 0) { // one STEP along the normal from the previous slab
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(slab.firstPixelCentre[c] - plan.slabs[k - 1].firstPixelCentre[c],
                                spacing.stepMm * p.normal[c], 1e-9);
            }
            const FloatImage image = grid.render(camera, W, H, RenderOptions{RenderMode::Aip, slab.slab});
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    Vec3 w = slab.firstPixelCentre;
                    for (int c = 0; c < 3; ++c)
                        w[c] += p.pixelSpacingMm * (x * p.rowDirection[c] + y * p.columnDirection[c]);
                    Vec3 front = w, back = w;
                    for (int c = 0; c < 3; ++c) {
                        front[c] -= 0.5 * spacing.thicknessMm * p.normal[c];
                        back[c] += 0.5 * spacing.thicknessMm * p.normal[c];
                    }
                    if (!insideGrid(v, front, 0.05) || !insideGrid(v, back, 0.05)) continue;
                    ASSERT_NEAR(image.at(x, y), field(w), 0.02)
                        << "camera az " << camera.azimuthDeg << " el " << camera.elevationDeg << " slab " << k
                        << " pixel " << x << "," << y;
                    ++checked;
                }
        }
        EXPECT_GT(checked, 200) << "camera az " << camera.azimuthDeg << " el " << camera.elevationDeg;
    }
}

} // namespace
