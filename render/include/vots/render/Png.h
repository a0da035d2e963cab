// PNG encoding of RGBA8 images through stb_image_write, decoding through stb_image, and an atomic file write.
#pragma once

#include "vots/render/Image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vots::render {

/// PNG bytes, 8 bit, opaque (the alpha channel is dropped; our images are always opaque): greyscale when
/// every pixel has r == g == b (the grey colour map), else RGB. Deterministic: the same image always
/// gives the same bytes.
std::vector<std::uint8_t> encodePng(const RgbaImage& image);

/// The RGBA pixels of a PNG (grey and RGB come back with r == g == b and alpha 255 as encodePng wrote
/// them); throws vots::fit::InputError for bytes that are not a PNG.
RgbaImage decodePng(const std::vector<std::uint8_t>& png);

/// Writes "<path>.tmp-<pid>" and renames it over path, so readers never see half a file.
/// Throws vots::fit::InputError when the file cannot be written.
void writePng(const std::string& path, const RgbaImage& image);

} // namespace vots::render
