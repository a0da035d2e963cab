// A thick slab: only the part of each ray within OFFSET +- THICKNESS/2 mm of the volume centre, measured
// along the viewing direction, counts in the projection.
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/RenderMode.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace vots::render {

struct Slab {
    double offsetMm = 0.0;    // signed distance of the slab's middle from the volume centre, along the view
    double thicknessMm = 1.0; // > 0
    friend bool operator==(const Slab&, const Slab&) = default;
};

/// Reads "OFFSET,THICKNESS" (two finite numbers in mm, thickness > 0); throws vots::fit::InputError.
Slab parseSlab(std::string_view text);
/// "OFFSET,THICKNESS" with every digit a float needs, for cache keys and URLs.
std::string formatSlab(const Slab& slab);

/// The slab in grid index space, for a camera and scene: a point x (index units) lies in it when
/// lo <= dot(normal, x) + offset <= hi. normal is the gradient of the signed distance in mm along the
/// camera's forward direction (the view axis, also for perspective), offset the distance of index 0.
struct SlabPlanes {
    std::array<double, 3> normal{0.0, 0.0, 1.0};
    double offset = 0.0;
    double lo = 0.0;
    double hi = 0.0;
};
SlabPlanes slabPlanesInIndexSpace(const Slab& slab, const Camera& camera, const SceneBounds& bounds);

/// What a renderer needs besides the camera and size: the projection and the slab, if any. Implicit from
/// a RenderMode, so a plain mode still reads as before.
struct RenderOptions {
    RenderMode mode = RenderMode::Mip;
    std::optional<Slab> slab; // nullopt: the whole ray through the volume
    /// Empty: the frame is drawn in one pass. Else the Vot walk in the fragment stage (llvmpipe's) draws
    /// the frame in bands of rows and asks this between them; true gives the frame up (FrameAbandoned),
    /// so that a large frame its client no longer wants holds the render thread for one band, not the
    /// whole frame. The bands give the same pixels as one pass.
    std::function<bool()> abandoned;

    RenderOptions(RenderMode m = RenderMode::Mip, std::optional<Slab> s = std::nullopt) // NOLINT: implicit
        : mode(m), slab(s) {}
};

} // namespace vots::render
