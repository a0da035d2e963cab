// The views of a turntable: N cameras evenly around the vertical axis, shared by `vots render` and GET
// /turntable.
#pragma once

#include "vots/render/Camera.h"

#include <optional>

namespace vots::render {

/// Most frames `vots render --turntable` draws (a tenth of a degree apart).
inline constexpr int MAX_TURNTABLE_FRAMES = 3600;

/// The camera of frame `index` (0 <= index < frames) of a turn that starts at `start`:
/// azimuth start + index * 360 / frames (less 360 where that passes 360, so it stays in the camera's
/// range), elevation `elevationDeg` where given, else the start's; zoom, pan and projection as the start.
/// The same double arithmetic everywhere, so a frame's camera text (formatCamera) names exactly the
/// frame a single `vots render --cam` or GET /render draws.
Camera turntableCamera(const Camera& start, int frames, int index, std::optional<double> elevationDeg);

} // namespace vots::render
