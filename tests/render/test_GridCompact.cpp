// The grid renderer draws a volume held in its 8- or 16-bit source type (integer textures) bit for bit as
// the same volume held as floats, in every mode, split into chunks or not.
#include "RenderTestSupport.h"

#include "vots/render/CameraText.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Slab.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using namespace vots;
using namespace vots::render;

namespace {

/// The float volume's samples (integers in T's range) held as T instead.
template <typename T> fit::Volume heldAs(const fit::Volume& floats) {
    fit::Volume compact = floats;
    std::vector<T> samples(floats.values.size());
    for (std::size_t i = 0; i < samples.size(); ++i)
        samples[i] = static_cast<T>(floats.values[i]);
    compact.values.clear();
    compact.compact = std::move(samples);
    return compact;
}

/// Integer samples from lo to hi with sharp ripples; x odd, so 8- and 16-bit rows do not fill 4 bytes.
fit::Volume integerVolume(double lo, double hi) {
    return test::sampleVolume({37, 30, 41}, [lo, hi](int x, int y, int z) {
        const double wave = 0.5 + 0.5 * std::sin(0.37 * x) * std::cos(0.23 * y + 0.11 * z);
        return std::round(lo + (hi - lo) * (z == 17 ? 1.0 : wave));
    });
}

std::size_t bitIdenticalPixels(const FloatImage& a, const FloatImage& b) {
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        same += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) == 0 ? 1 : 0;
    return same;
}

void expectSameImages(const fit::Volume& floats, const fit::Volume& compact, int chunkPlanes,
                      const std::string& what) {
    ASSERT_TRUE(compact.isCompact()) << what;
    GridRenderer fromFloats, fromCompact;
    fromFloats.setChunkPlaneLimit(chunkPlanes);
    fromCompact.setChunkPlaneLimit(chunkPlanes);
    fromFloats.upload(floats);
    fromCompact.upload(compact);
    ASSERT_EQ(fromFloats.chunkCount(), fromCompact.chunkCount()) << what;
    EXPECT_EQ(fromFloats.valueRange(), fromCompact.valueRange()) << what;
    for (const char* text : {"anterior", "az=30,el=20", "az=-50,el=-30,zoom=1.4,proj=persp,fov=40"}) {
        const Camera cam = parseCamera(text);
        for (const RenderOptions& options :
             {RenderOptions{RenderMode::Mip}, RenderOptions{RenderMode::MinIp},
              RenderOptions{RenderMode::Aip}, RenderOptions{RenderMode::Mip, Slab{3.0, 8.0}}}) {
            const FloatImage a = fromFloats.render(cam, 64, 56, options);
            const FloatImage b = fromCompact.render(cam, 64, 56, options);
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            EXPECT_EQ(bitIdenticalPixels(a, b), a.pixels.size())
                << what << " " << text << " " << renderModeName(options.mode)
                << (options.slab ? " slab" : "");
        }
    }
}

} // namespace

TEST(GridCompact, EachSourceTypeDrawsAsItsFloats) {
    test::glContext();
    const fit::Volume int16s = integerVolume(-1024.0, 3071.0); // CT's range
    expectSameImages(int16s, heldAs<std::int16_t>(int16s), 0, "int16");
    const fit::Volume extremes = integerVolume(-32768.0, 32767.0);
    expectSameImages(extremes, heldAs<std::int16_t>(extremes), 0, "int16 full range");
    const fit::Volume uint16s = integerVolume(0.0, 65535.0);
    expectSameImages(uint16s, heldAs<std::uint16_t>(uint16s), 0, "uint16");
    const fit::Volume uint8s = integerVolume(0.0, 255.0);
    expectSameImages(uint8s, heldAs<std::uint8_t>(uint8s), 0, "uint8");
    const fit::Volume int8s = integerVolume(-128.0, 127.0);
    expectSameImages(int8s, heldAs<std::int8_t>(int8s), 0, "int8");
}

TEST(GridCompact, ChunkedCompactVolumesDrawAsTheirFloats) {
    test::glContext();
    const fit::Volume int16s = integerVolume(-1024.0, 3071.0);
    expectSameImages(int16s, heldAs<std::int16_t>(int16s), 12, "int16 in chunks of 12 planes");
}

TEST(GridCompact, AFloatVolumeStillDrawsAfterACompactOne) {
    // The renderer keeps one program per texel type: switching back must read float textures again.
    test::glContext();
    const fit::Volume floats = integerVolume(0.0, 255.0);
    GridRenderer grid, reference;
    reference.upload(floats);
    grid.upload(heldAs<std::uint8_t>(floats));
    grid.upload(floats);
    const Camera cam = parseCamera("az=30,el=20");
    const FloatImage a = reference.render(cam, 48, 40, RenderMode::Mip);
    const FloatImage b = grid.render(cam, 48, 40, RenderMode::Mip);
    EXPECT_EQ(bitIdenticalPixels(a, b), a.pixels.size());
}
