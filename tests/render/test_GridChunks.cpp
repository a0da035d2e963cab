// The grid renderer split into z chunks (volumes deeper than one 3D texture) gives the unsplit image in
// every mode.
#include "RenderTestSupport.h"

#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

using namespace vots;
using namespace vots::render;

TEST(GridChunks, ChunksGiveTheImageOfOneTexture) {
    test::glContext();
    // Sharp features across the chunk faces: a bright ridge in z and ripples in every axis.
    const fit::Volume volume = test::sampleVolume({37, 30, 71}, [](int x, int y, int z) {
        return 100.0 * std::sin(0.37 * x) * std::cos(0.23 * y + 0.11 * z) +
               (z == 23 || z == 24 ? 150.0 : 0.0);
    });
    GridRenderer whole, chunks;
    whole.upload(volume);
    chunks.setChunkPlaneLimit(12); // chunks of 11 cells: faces at z = 11, 22, 33, ...
    chunks.upload(volume);
    ASSERT_EQ(whole.chunkCount(), 1);
    ASSERT_EQ(chunks.chunkCount(), 7);
    const auto range = whole.valueRange();
    for (const char* text :
         {"anterior", "superior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40",
          "az=20,el=10,zoom=6,proj=persp,fov=60", "az=0,el=89.5"}) {
        const Camera cam = parseCamera(text);
        for (const RenderOptions& options :
             {RenderOptions{RenderMode::Mip}, RenderOptions{RenderMode::MinIp},
              RenderOptions{RenderMode::Aip}, RenderOptions{RenderMode::Aip, Slab{2.0, 9.0}}}) {
            const FloatImage a = whole.render(cam, 90, 80, options);
            const FloatImage b = chunks.render(cam, 90, 80, options);
            // The same cells along every ray; mip and minip differ only where a chunk face rounds the
            // walk's t differently, aip also by the order of the float sum (each chunk adds its part).
            const test::ImageComparison c = test::compareImages(a, b, 1e-5 * (range[1] - range[0]));
            const std::string what = std::string(text) + " " + std::string(renderModeName(options.mode)) +
                                     (options.slab ? " slab" : "");
            std::cout << what << ": " << c.bitIdentical << " of " << a.pixels.size()
                      << " bit-identical, worst " << c.worst << "\n";
            EXPECT_EQ(c.finiteMismatch, 0u) << what;
            EXPECT_EQ(c.beyondTolerance, 0u) << what;
        }
    }
}

TEST(GridChunks, UnsplitVolumesKeepOneTexture) {
    test::glContext();
    const fit::Volume volume = test::sampleVolume({9, 8, 12}, [](int x, int y, int z) { return x + y + z; });
    GridRenderer grid;
    grid.setChunkPlaneLimit(12);
    grid.upload(volume);
    EXPECT_EQ(grid.chunkCount(), 1);
    EXPECT_THROW(grid.setChunkPlaneLimit(3), fit::InputError);
}
