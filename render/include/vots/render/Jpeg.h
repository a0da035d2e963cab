// JPEG encoding of RGBA8 images through libjpeg-turbo, for the viewer socket's drafts, and decoding for
// tests.
#pragma once

#include "vots/render/Image.h"

#include <cstdint>
#include <vector>

namespace vots::render {

/// JPEG bytes at quality 1..100 (baseline, 4:2:0 chroma): one grey channel when every pixel has
/// r == g == b (the grey colour map), else YCbCr. Alpha is dropped (our images are opaque). Throws
/// fit::InputError for an empty image or a quality outside 1..100.
std::vector<std::uint8_t> encodeJpeg(const RgbaImage& image, int quality);

/// The RGBA pixels of a JPEG (alpha 255). Throws fit::InputError for bytes libjpeg cannot decode.
RgbaImage decodeJpeg(const std::vector<std::uint8_t>& jpeg);

} // namespace vots::render
