// JPEG drafts: they decode back to the frame's size and pixels within JPEG's error, grey stays grey,
// and bad input is an error, never a crash.
#include "vots/fit/Error.h"
#include "vots/render/Jpeg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace vots::render {
namespace {

RgbaImage gradient(int width, int height, bool grey) {
    RgbaImage image{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 4)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = &image.pixels[(static_cast<std::size_t>(y) * width + x) * 4];
            const auto v = static_cast<std::uint8_t>((x * 255) / (width - 1));
            p[0] = v;
            p[1] = grey ? v : static_cast<std::uint8_t>((y * 255) / (height - 1));
            p[2] = grey ? v : 128;
            p[3] = 255;
        }
    return image;
}

double meanAbsoluteError(const RgbaImage& a, const RgbaImage& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        sum += std::abs(int(a.pixels[i]) - int(b.pixels[i]));
    return sum / static_cast<double>(a.pixels.size());
}

TEST(Jpeg, RoundTripKeepsSizeAndPixelsWithinJpegError) {
    for (const bool grey : {true, false}) {
        const RgbaImage image = gradient(97, 61, grey);
        const std::vector<std::uint8_t> jpeg = encodeJpeg(image, 70);
        ASSERT_GE(jpeg.size(), 4u);
        EXPECT_EQ(jpeg[0], 0xFF);
        EXPECT_EQ(jpeg[1], 0xD8); // start of image
        const RgbaImage back = decodeJpeg(jpeg);
        ASSERT_EQ(back.width, 97);
        ASSERT_EQ(back.height, 61);
        EXPECT_LT(meanAbsoluteError(image, back), 4.0) << (grey ? "grey" : "colour");
        if (grey) {
            for (std::size_t i = 0; i < back.pixels.size(); i += 4)
                ASSERT_TRUE(back.pixels[i] == back.pixels[i + 1] && back.pixels[i] == back.pixels[i + 2]);
        }
    }
}

TEST(Jpeg, HigherQualityIsCloser) {
    const RgbaImage image = gradient(128, 128, false);
    const double low = meanAbsoluteError(image, decodeJpeg(encodeJpeg(image, 10)));
    const double high = meanAbsoluteError(image, decodeJpeg(encodeJpeg(image, 95)));
    EXPECT_LT(high, low);
}

TEST(Jpeg, BadInputIsAnError) {
    EXPECT_THROW(encodeJpeg(RgbaImage{}, 70), fit::InputError);
    EXPECT_THROW(encodeJpeg(gradient(8, 8, true), 0), fit::InputError);
    EXPECT_THROW(encodeJpeg(gradient(8, 8, true), 101), fit::InputError);
    EXPECT_THROW(decodeJpeg({}), fit::InputError);
    EXPECT_THROW(decodeJpeg({0xFF, 0xD8, 0x00, 0x12, 0x34}), fit::InputError);
    std::vector<std::uint8_t> cut = encodeJpeg(gradient(64, 64, false), 70);
    cut.resize(cut.size() / 3);
    // libjpeg pads a truncated stream with grey and warns; it must not crash or read past the bytes.
    try {
        const RgbaImage image = decodeJpeg(cut);
        EXPECT_EQ(image.width, 64);
    } catch (const fit::InputError&) {
    }
}

} // namespace
} // namespace vots::render
