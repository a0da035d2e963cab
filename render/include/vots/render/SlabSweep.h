// A slab sweep: thick slabs THICKNESS mm apart by STEP mm along the view through the whole volume, one
// frame each, with each image's place in patient space (for a derived DICOM series).
#pragma once

#include "vots/render/Camera.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/Slab.h"

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace vots::render {

/// Most slabs one sweep draws.
inline constexpr int MAX_SWEEP_SLABS = 4096;

struct SlabSweepSpacing {
    double thicknessMm = 10.0; // > 0
    double stepMm = 5.0;       // > 0, between the middles of neighbouring slabs
};

/// Reads "THICKNESS,STEP" (two finite numbers in mm, both > 0); throws vots::fit::InputError.
SlabSweepSpacing parseSlabSweep(std::string_view text);

/// Where a frame's pixels lie in patient space (LPS, mm) on the slab's middle plane: pixel (x, y) (y = 0
/// the top row) at firstPixelCentre + x * spacing * rowDirection + y * spacing * columnDirection. The
/// normal rowDirection x columnDirection is the view direction.
struct SweepImagePlane {
    std::array<double, 3> rowDirection{1, 0, 0};
    std::array<double, 3> columnDirection{0, 1, 0};
    std::array<double, 3> normal{0, 0, 1};
    double pixelSpacingMm = 1.0;
};

struct SweepSlab {
    Slab slab; // offset from the volume centre along the view, and the sweep's thickness
    std::array<double, 3> firstPixelCentre{0, 0, 0};
};

struct SlabSweepPlan {
    SweepImagePlane plane;
    std::vector<SweepSlab> slabs; // in order along the normal, STEP mm apart
};

/// The slabs of a sweep through the volume the bounds describe, seen by an orthographic camera at
/// width x height. With L the extent of the grid's corners along the view, there are
/// n = 1 + ceil((L - THICKNESS) / STEP) slabs (at least 1), and the run they cover, THICKNESS + (n-1) STEP
/// long, is centred on the volume, so the first and last reach equally far past its ends. The pixel
/// spacing is the camera's: 2 R / (zoom * height), R the half-diagonal of the volume's patient-space box
/// (square pixels; the image height shows the whole volume at zoom 1). The positions come from the
/// renderer's own pixel-centre rays (computeCameraMatrices). Throws fit::InputError for a perspective
/// camera or more than MAX_SWEEP_SLABS slabs.
SlabSweepPlan planSlabSweep(const SlabSweepSpacing& spacing, const Camera& camera, const SceneBounds& bounds,
                            int width, int height);

/// `first` with the slab of sweep slab `slab`: the frame that draws it.
FrameRequest sweepFrame(const FrameRequest& first, const SweepSlab& slab);

/// "axial", "coronal" or "sagittal" for a normal along one patient axis (within 1e-6), else "oblique".
std::string_view sweepPlaneName(const std::array<double, 3>& normal);

/// The series' description: mode, thickness, step and plane, e.g. "MIP 10 mm / 5 mm axial".
std::string sweepDescription(RenderMode mode, const SlabSweepSpacing& spacing,
                             const std::array<double, 3>& normal);

} // namespace vots::render
