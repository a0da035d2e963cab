// The pixels of an opaque RGBA image as the encoders take them: one grey channel when it is grey, else RGB.
#pragma once

#include "vots/render/Image.h"

#include <cstdint>
#include <vector>

namespace vots::render {

/// The pixels as grey (channels = 1) when r == g == b everywhere, else as RGB (channels = 3); alpha is
/// dropped. A grey frame (the grey colour map) then costs a third of the bytes to compress.
std::vector<std::uint8_t> opaqueChannels(const RgbaImage& image, int& channels);

} // namespace vots::render
