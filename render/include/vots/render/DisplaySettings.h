// Window/level and colour map that turn a float image into RGBA8 (the display pass).
#pragma once

#include "vots/render/Colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace vots::render {

/// Maps value v to colormap index round(255 * clamp((v - (level - width/2)) / width, 0, 1)).
/// Non-finite values (background: no Vot or sample contributed) show as entry 0, the window's low end.
struct DisplaySettings {
    float level = 0.f; // window centre, data units (HU for CT)
    float width = 1.f; // window width, data units, > 0
    Colormap colormap = Colormap::Grey;

    float low() const { return level - 0.5f * width; }
    float high() const { return level + 0.5f * width; }
    friend bool operator==(const DisplaySettings&, const DisplaySettings&) = default;
};

/// Window covering [lo, hi] exactly (width at least a tiny positive number).
DisplaySettings windowForRange(float lo, float hi, Colormap map = Colormap::Grey);

/// Parses "level,width" (finite numbers, width > 0); throws vots::fit::InputError.
DisplaySettings parseWindow(std::string_view text, Colormap map = Colormap::Grey);

/// The colormap index of one value: the display pass's rule (applyDisplay), inline for its per-pixel loop.
inline int displayIndex(float value, const DisplaySettings& settings) {
    if (!std::isfinite(value)) return 0;
    const float t = std::clamp((value - settings.low()) / settings.width, 0.f, 1.f);
    return static_cast<int>(std::floor(255.f * t + 0.5f));
}

} // namespace vots::render
