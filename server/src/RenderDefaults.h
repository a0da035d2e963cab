// The display window a /render request gets when it names none, per mode (same rule as `vots render`).
#pragma once

#include "vots/render/DisplaySettings.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/Params.h"

#include <array>

namespace vots::server {

/// The request's window, or: the full data range for mip and reference, the renderer's density range
/// for density. The colormap is always the request's.
inline render::DisplaySettings displayFor(const RenderParams& p, std::array<float, 2> valueRange,
                                          const render::VotRenderer& vots) {
    if (p.window) return *p.window;
    if (p.mode == render::RenderMode::Density) {
        const auto range = vots.densityRange();
        return render::windowForRange(range[0], range[1], p.colormap);
    }
    return render::windowForRange(valueRange[0], valueRange[1], p.colormap);
}

} // namespace vots::server
