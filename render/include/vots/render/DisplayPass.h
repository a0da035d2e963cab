// The display pass on its own: window/level + colour map of any float image on the GPU.
#pragma once

#include "vots/render/DisplaySettings.h"
#include "vots/render/Image.h"

namespace vots::render {

/// Uploads the image and runs the same shader the renderers' renderRgba() use (e.g. to re-window
/// without re-rendering). Needs a current EglContext.
RgbaImage applyDisplay(const FloatImage& image, const DisplaySettings& display);

} // namespace vots::render
