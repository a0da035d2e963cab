// PNG encoding: decodes back to the same pixels, greyscale only when every pixel is grey, and the same
// image always gives the same bytes.
#include "vots/fit/Error.h"
#include "vots/render/Png.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstdlib>
#include <memory>

using namespace vots::render;

namespace {

RgbaImage gradient(int width, int height, bool grey) {
    RgbaImage image;
    image.width = width;
    image.height = height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto v = static_cast<std::uint8_t>((x * 7 + y * 13) & 0xff);
            image.pixels.insert(image.pixels.end(), {v, grey ? v : static_cast<std::uint8_t>(255 - v),
                                                     grey ? v : static_cast<std::uint8_t>(x & 0xff), 255});
        }
    return image;
}

struct Decoded {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> rgba;
};

Decoded decode(const std::vector<std::uint8_t>& png) {
    Decoded d;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &d.width, &d.height, &d.channels, 4),
        stbi_image_free);
    if (pixels) d.rgba.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(d.width) * d.height * 4);
    return d;
}

} // namespace

TEST(Png, ColourImageRoundTripsAsRgb) {
    const RgbaImage image = gradient(67, 41, false);
    const Decoded d = decode(encodePng(image));
    EXPECT_EQ(d.width, 67);
    EXPECT_EQ(d.height, 41);
    EXPECT_EQ(d.channels, 3);
    EXPECT_EQ(d.rgba, image.pixels);
}

TEST(Png, GreyImageRoundTripsAsOneChannel) {
    const RgbaImage image = gradient(64, 33, true);
    const std::vector<std::uint8_t> png = encodePng(image);
    const Decoded d = decode(png);
    EXPECT_EQ(d.channels, 1);
    EXPECT_EQ(d.rgba, image.pixels);
    // One grey pixel more or less decides the format: a single coloured pixel makes it RGB.
    RgbaImage tinted = image;
    tinted.pixels[4 * 100 + 1] ^= 1;
    const Decoded t = decode(encodePng(tinted));
    EXPECT_EQ(t.channels, 3);
    EXPECT_EQ(t.rgba, tinted.pixels);
    EXPECT_EQ(encodePng(image), png);
}

TEST(Png, RefusesImpossibleSizes) {
    RgbaImage empty;
    EXPECT_THROW(encodePng(empty), vots::fit::InputError);
}
