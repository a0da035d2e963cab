// CPU-side images handed out by the renderers: one float channel (MIP values) or RGBA8 (display).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vots::render {

/// One float per pixel, row 0 is the TOP row of the picture (PNG order), x to the right.
/// MIP images hold data values (e.g. HU); a pixel no Vot or sample reached holds -infinity.
/// Density images hold log2 of a box size (see VotRenderer) and +infinity where no box was hit.
struct FloatImage {
    int width = 0;
    int height = 0;
    std::vector<float> pixels; // width * height, row-major, top row first

    float at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

/// 8-bit RGBA, row 0 is the top row, 4 bytes per pixel, alpha always 255.
struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels; // width * height * 4

    const std::uint8_t* at(int x, int y) const {
        return &pixels[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

/// Largest accepted width or height; renderers throw fit::InputError outside 1..MAX_IMAGE_SIDE.
inline constexpr int MAX_IMAGE_SIDE = 8192;

/// Throws vots::fit::InputError ("image size WxH outside 1..8192") unless both sides are valid.
void checkImageSize(int width, int height);

} // namespace vots::render
