// The grid renderer drawing one z slab of a volume (a rank's share under mpirun): slabs combined by max,
// min or sum give the image of one upload split into the same chunks, bit for bit.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/fit/VolumePlanes.h"
#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace vots;
using namespace vots::render;

namespace {

// Sharp features across the slab faces: a bright ridge in z and ripples in every axis.
fit::Volume ridgedVolume() {
    return test::sampleVolume({23, 19, 34}, [](int x, int y, int z) {
        return 100.0 * std::sin(0.37 * x) * std::cos(0.23 * y + 0.11 * z) +
               (z == 10 || z == 11 ? 150.0 : 0.0);
    });
}

// What the ranks' composite does with their frames, in rank order.
void combine(RenderMode mode, FloatImage& into, const FloatImage& next) {
    for (std::size_t i = 0; i < into.pixels.size(); ++i) {
        float& v = into.pixels[i];
        const float w = next.pixels[i];
        v = mode == RenderMode::Mip ? std::max(v, w) : mode == RenderMode::MinIp ? std::min(v, w) : v + w;
    }
}

} // namespace

TEST(GridSlabs, SlabsCombineToTheImageOfTheSameChunks) {
    test::glContext();
    const fit::Volume volume = ridgedVolume();
    GridRenderer chunked;
    chunked.setChunkPlaneLimit(12); // chunks own cells [0, 11), [11, 22), [22, 33)
    chunked.upload(volume);
    ASSERT_EQ(chunked.chunkCount(), 3);
    const fit::Volume whole = fit::gridOf(volume);
    std::vector<GridRenderer> slabs(3);
    for (int k = 0; k < 3; ++k) {
        slabs[k].uploadPlanes(fit::planesOf(volume, 11 * k, 11 * (k + 1)), 11 * k, whole);
        ASSERT_EQ(slabs[k].chunkCount(), 1);
        EXPECT_EQ(slabs[k].bounds().dims, volume.dims); // the camera frames the whole grid on every slab
    }
    for (const char* text : {"anterior", "superior", "az=30,el=20",
                             "az=-50,el=-30,zoom=1.4,proj=persp,fov=40", "az=0,el=89.5"}) {
        const Camera cam = parseCamera(text);
        for (const RenderOptions& options :
             {RenderOptions{RenderMode::Mip}, RenderOptions{RenderMode::MinIp},
              RenderOptions{RenderMode::Aip}, RenderOptions{RenderMode::Aip, Slab{2.0, 9.0}},
              RenderOptions{RenderMode::Mip, Slab{-3.0, 6.0}}}) {
            const std::string what = std::string(text) + " " + std::string(renderModeName(options.mode)) +
                                     (options.slab ? " slab" : "");
            const FloatImage want = chunked.render(cam, 72, 64, options);
            FloatImage got = slabs[0].render(cam, 72, 64, options);
            for (int k = 1; k < 3; ++k)
                combine(options.mode, got, slabs[k].render(cam, 72, 64, options));
            ASSERT_EQ(got.pixels.size(), want.pixels.size()) << what;
            EXPECT_EQ(test::compareImages(got, want, 0.0).bitIdentical, want.pixels.size()) << what;
        }
    }
}

TEST(GridSlabs, APlaneWithoutCellsDrawsNothingAndBadSlabsAreRefused) {
    test::glContext();
    const fit::Volume volume = ridgedVolume();
    const fit::Volume whole = fit::gridOf(volume);
    GridRenderer grid;
    grid.uploadPlanes(fit::planesOf(volume, 33, 33), 33, whole); // more ranks than cells: the last plane
    EXPECT_EQ(grid.chunkCount(), 0);
    const Camera cam = parseCamera("az=30,el=20");
    for (const float v : grid.render(cam, 32, 24, RenderMode::Mip).pixels)
        EXPECT_EQ(v, -INFINITY);
    for (const float v : grid.render(cam, 32, 24, RenderMode::MinIp).pixels)
        EXPECT_EQ(v, INFINITY);
    EXPECT_THROW(grid.uploadPlanes(fit::planesOf(volume, 30, 33), 31, whole), fit::InputError);
    EXPECT_THROW(grid.uploadPlanes(fit::planesOf(volume, 0, 3), -1, whole), fit::InputError);
}
