// The grid renderer's mip, minip and aip are the exact max, min and mean of the trilinear interpolant
// along each ray, clipped exactly to the slab.
#include "RenderTestSupport.h"

#include "vots/fit/VolumeLoad.h"
#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>

using namespace vots;
using namespace vots::render;

// Fields equal to their own trilinear interpolant: a linear one, and a product of one linear function per
// axis whose cubic along a diagonal ray peaks strictly between samples.
TEST(GridExact, ModesAreTheExactMaxMinAndMeanAlongRays) {
    test::glContext();
    const std::array<int, 3> dims{21, 17, 25};
    const std::function<double(double, double, double)> fields[] = {
        [](double x, double y, double z) { return 0.03 * x - 0.05 * y + 0.02 * z + 0.4; },
        [](double x, double y, double z) { return x * y * (24.0 - z) / (20.0 * 16.0 * 24.0); }};
    for (int k = 0; k < 2; ++k) {
        const auto& f = fields[k];
        const fit::Volume volume = test::sampleVolume(dims, [&](int x, int y, int z) { return f(x, y, z); });
        GridRenderer grid;
        grid.upload(volume);
        for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
            const Camera cam = parseCamera(text);
            const int w = 41, h = 37;
            const CameraMatrices m = computeCameraMatrices(cam, grid.bounds(), w, h);
            const FloatImage mip = grid.render(cam, w, h, RenderMode::Mip);
            const FloatImage minip = grid.render(cam, w, h, RenderMode::MinIp);
            const FloatImage aip = grid.render(cam, w, h, RenderMode::Aip);
            // Values are O(1); the float cubic per cell and the float sum over ~50 cells stay within 1e-4.
            constexpr double TOLERANCE = 1e-4;
            std::size_t compared = 0, edge = 0;
            double worst = 0;
            for (int py = 0; py < h; ++py)
                for (int px = 0; px < w; ++px) {
                    const test::RayProfile s = test::cpuRayProfile(m, dims, w, h, px, py, f, 4000);
                    const bool hit = std::isfinite(s.max);
                    const float gpu = mip.at(px, py);
                    if (hit != std::isfinite(gpu)) { // a ray grazing the box: float vs double
                        ++edge;
                        continue;
                    }
                    if (!hit) {
                        EXPECT_EQ(minip.at(px, py), INFINITY);
                        EXPECT_EQ(aip.at(px, py), -INFINITY);
                        continue;
                    }
                    ++compared;
                    const double d = std::max({std::abs(gpu - s.max), std::abs(minip.at(px, py) - s.min),
                                               std::abs(aip.at(px, py) - s.mean)});
                    worst = std::max(worst, d);
                    EXPECT_NEAR(gpu, s.max, TOLERANCE)
                        << text << " field " << k << " pixel " << px << "," << py;
                    EXPECT_NEAR(minip.at(px, py), s.min, TOLERANCE) << text << " field " << k;
                    EXPECT_NEAR(aip.at(px, py), s.mean, TOLERANCE) << text << " field " << k;
                }
            std::cout << text << " field " << k << ": " << compared << " rays, worst " << worst << ", "
                      << edge << " grazing\n";
            EXPECT_GT(compared, std::size_t(w * h / 4)) << text;
            EXPECT_LE(edge, std::size_t(w * h / 100)) << text;
        }
    }
}

TEST(GridExact, MinBelowMeanBelowMaxOnRealCt) {
    test::glContext();
    const fit::Volume volume =
        fit::loadVolume(std::string(VOTS_TEST_DATA_DIR) + "/cranium-quarter_64x64x108_int16.nrrd");
    GridRenderer grid;
    grid.upload(volume);
    const auto range = grid.valueRange();
    const double tolerance = 1e-5 * (range[1] - range[0]);
    for (const char* text : {"az=30,el=20", "left", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        const FloatImage mip = grid.render(cam, 96, 96, RenderMode::Mip);
        const FloatImage minip = grid.render(cam, 96, 96, RenderMode::MinIp);
        const FloatImage aip = grid.render(cam, 96, 96, RenderMode::Aip);
        std::size_t hits = 0;
        for (std::size_t i = 0; i < mip.pixels.size(); ++i) {
            const bool hit = std::isfinite(mip.pixels[i]);
            ASSERT_EQ(hit, std::isfinite(minip.pixels[i])) << text << " pixel " << i;
            ASSERT_EQ(hit, std::isfinite(aip.pixels[i])) << text << " pixel " << i;
            if (!hit) continue;
            ++hits;
            EXPECT_LE(minip.pixels[i], aip.pixels[i] + tolerance)
                << text << " pixel " << i << " mip " << mip.pixels[i] << " aip " << aip.pixels[i];
            EXPECT_LE(aip.pixels[i], mip.pixels[i] + tolerance) << text << " pixel " << i;
            EXPECT_GE(minip.pixels[i], range[0] - tolerance);
            EXPECT_LE(mip.pixels[i], range[1] + tolerance);
        }
        EXPECT_GT(hits, mip.pixels.size() / 4) << text;
    }
}

// The field is the slab's own signed distance (linear, so trilinear-exact): inside the slab a ray sees
// exactly [lo, hi], so the slab's far plane bounds the mip (nothing brighter beyond it is seen) and a ray
// crossing the whole slab has mip = hi, minip = lo and aip = their middle.
TEST(GridExact, SlabPlanesAreHonouredExactly) {
    test::glContext();
    const std::array<int, 3> dims{30, 26, 34};
    for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        const Slab slab{1.5, 6.0};
        const fit::Volume probe = test::sampleVolume(dims, [](int, int, int) { return 0.0; });
        const SlabPlanes planes = slabPlanesInIndexSpace(slab, cam, sceneBounds(probe));
        const fit::Volume volume = test::sampleVolume(dims, [&](int x, int y, int z) {
            return planes.normal[0] * x + planes.normal[1] * y + planes.normal[2] * z + planes.offset;
        });
        GridRenderer grid;
        grid.upload(volume);
        const int w = 45, h = 41;
        const FloatImage whole = grid.render(cam, w, h, RenderMode::Mip);
        const FloatImage mip = grid.render(cam, w, h, {RenderMode::Mip, slab});
        const FloatImage minip = grid.render(cam, w, h, {RenderMode::MinIp, slab});
        const FloatImage aip = grid.render(cam, w, h, {RenderMode::Aip, slab});
        constexpr double TOLERANCE = 1e-4; // values are O(10) mm; float plane crossings
        std::size_t inside = 0, cutAway = 0;
        for (std::size_t i = 0; i < mip.pixels.size(); ++i) {
            if (!std::isfinite(mip.pixels[i])) {
                EXPECT_FALSE(std::isfinite(aip.pixels[i]));
                EXPECT_FALSE(std::isfinite(minip.pixels[i]));
                continue;
            }
            EXPECT_LE(mip.pixels[i], planes.hi + TOLERANCE) << text << " pixel " << i;
            EXPECT_GE(minip.pixels[i], planes.lo - TOLERANCE) << text << " pixel " << i;
            if (whole.pixels[i] > planes.hi + 1.0) ++cutAway; // brighter parts beyond the slab, unseen
            // A ray crossing the whole slab inside the volume sees both planes.
            if (std::abs(mip.pixels[i] - planes.hi) < TOLERANCE &&
                std::abs(minip.pixels[i] - planes.lo) < TOLERANCE) {
                ++inside;
                EXPECT_NEAR(aip.pixels[i], 0.5 * (planes.lo + planes.hi), TOLERANCE)
                    << text << " pixel " << i;
            }
        }
        std::cout << text << ": " << inside << " rays cross the whole slab, " << cutAway
                  << " see brighter samples without it\n";
        EXPECT_GT(inside, mip.pixels.size() / 10) << text;
        EXPECT_GT(cutAway, mip.pixels.size() / 10) << text;
        const int cx = w / 2, cy = h / 2; // the centre ray crosses the whole slab (offset 1.5 mm, 6 mm thick)
        EXPECT_NEAR(mip.at(cx, cy), planes.hi, TOLERANCE) << text;
        EXPECT_NEAR(minip.at(cx, cy), planes.lo, TOLERANCE) << text;
    }
}

TEST(GridExact, SlabThickerThanTheVolumeGivesTheWholeImage) {
    test::glContext();
    const fit::Volume volume = test::sampleVolume(
        {19, 23, 17}, [](int x, int y, int z) { return std::sin(0.5 * x) * std::cos(0.3 * y) + 0.1 * z; });
    GridRenderer grid;
    grid.upload(volume);
    for (const RenderMode mode : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip})
        for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
            const Camera cam = parseCamera(text);
            const FloatImage a = grid.render(cam, 40, 36, mode);
            const FloatImage b = grid.render(cam, 40, 36, {mode, Slab{0.0, 1e4}});
            const test::ImageComparison c = test::compareImages(a, b, 0.0);
            EXPECT_EQ(c.bitIdentical, a.pixels.size()) << text << " " << renderModeName(mode);
        }
}

// NaN samples (no data, x >= 15 here): a cell with a NaN corner adds nothing to mip and counts as the
// lowest finite sample in minip and aip; rays through finite cells only are drawn as without the NaNs.
TEST(GridExact, CellsWithNanCornersAreNoData) {
    test::glContext();
    const std::array<int, 3> dims{21, 17, 25};
    const auto f = [](int x, int y, int z) { return 0.03 * x - 0.05 * y + 0.02 * z + 0.4; };
    const fit::Volume whole = test::sampleVolume(dims, f);
    fit::Volume holed = whole;
    for (int z = 0; z < dims[2]; ++z)
        for (int y = 0; y < dims[1]; ++y)
            for (int x = 15; x < dims[0]; ++x)
                holed.values[holed.indexOf(x, y, z)] = std::numeric_limits<float>::quiet_NaN();
    const float lowest = holed.valueRange()[0];
    EXPECT_FLOAT_EQ(lowest, static_cast<float>(f(0, 16, 0)));
    GridRenderer a, b;
    a.upload(whole);
    b.upload(holed);
    const Camera cam = parseCamera("anterior"); // rays along y: each image column is one x
    const int w = 41, h = 37;
    std::array<FloatImage, 3> full, part;
    const RenderMode modes[] = {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip};
    for (int m = 0; m < 3; ++m) {
        full[m] = a.render(cam, w, h, modes[m]);
        part[m] = b.render(cam, w, h, modes[m]);
    }
    std::size_t hits = 0, same = 0, noData = 0;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            for (int m = 0; m < 3; ++m)
                ASSERT_FALSE(std::isnan(part[m].at(px, py))) << px << "," << py;
            if (!std::isfinite(full[0].at(px, py))) continue; // the ray misses the grid
            ++hits;
            bool equal = true;
            for (int m = 0; m < 3; ++m)
                equal = equal && std::abs(part[m].at(px, py) - full[m].at(px, py)) <= 1e-6f;
            same += equal ? 1 : 0;
            if (part[0].at(px, py) == -INFINITY) { // every cell of the ray is no data
                EXPECT_FLOAT_EQ(part[1].at(px, py), lowest);
                EXPECT_FLOAT_EQ(part[2].at(px, py), lowest);
                ++noData;
            }
        }
    // 14 of the 20 cells across are finite, 6 no data: rays split about so (the boundary column aside).
    EXPECT_GT(same, hits / 2);
    EXPECT_GT(noData, hits / 5);
    std::cout << hits << " rays: " << same << " as without NaNs, " << noData << " through no data only\n";
}
