// The display pass: window/level + colour map of any float image, on the CPU (no GL context needed).
#pragma once

#include "vots/render/DisplaySettings.h"
#include "vots/render/Image.h"

namespace vots::render {

/// RGBA8 of `image` (top row first), each pixel colormapTable(display.colormap)[displayIndex(v, display)].
/// Throws fit::GraphicsError for an image whose size and pixels disagree or a window width not > 0.
RgbaImage applyDisplay(const FloatImage& image, const DisplaySettings& display);

} // namespace vots::render
