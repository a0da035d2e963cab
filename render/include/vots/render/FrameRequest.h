// One frame as `vots render` and GET /render ask for it: camera, size, mode, window, colour map, defaults.
#pragma once

#include "vots/fit/Fitter.h"
#include "vots/render/Camera.h"
#include "vots/render/Colormap.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/Image.h"
#include "vots/render/RenderMode.h"
#include "vots/render/Slab.h"

#include <array>
#include <functional>
#include <optional>
#include <string_view>

namespace vots::render {

class GridRenderer;
class VotRenderer;

inline constexpr int DEFAULT_FRAME_SIDE = 512;
/// Largest side GET /render draws: each frame is one HTTP answer a browser decodes. `vots render`
/// allows MAX_IMAGE_SIDE, what the renderers accept.
inline constexpr int MAX_SERVED_SIDE = 4096;

/// A fit made to be rendered certifies cells, not only samples: a MIP picks up the overshoot between
/// samples, so the bound must hold there too (docs/DESIGN.md §3).
inline constexpr fit::Certify RENDER_FIT_CERTIFY = fit::Certify::Cells;

/// The options of a fit made to be rendered, built here for the server, `vots render` and the benchmarks:
/// eps in data units, the degree, the background threshold (nullopt: every cell is fitted), what the
/// bound is certified on and the norm a box is accepted by (docs/DESIGN.md §3). Progress, cancel, focus
/// and threads are left for the caller.
fit::FitOptions renderFitOptions(float eps, int degree, std::optional<float> background,
                                 fit::Certify certify = RENDER_FIT_CERTIFY,
                                 fit::FitNorm norm = fit::DEFAULT_FIT_NORM);

struct FrameRequest {
    Camera camera = cameraForView(ViewPreset::Anterior);
    int width = DEFAULT_FRAME_SIDE;
    int height = DEFAULT_FRAME_SIDE;
    RenderMode mode = RenderMode::Mip;
    RendererKind renderer = RendererKind::Vots;
    std::optional<Slab> slab;              // nullopt: whole rays
    std::optional<DisplaySettings> window; // nullopt: the full range (see renderFrame)
    Colormap colormap = Colormap::Grey;
};

/// Sets mode, renderer and slab from the --mode / mode=, --renderer / renderer= and --slab / slab= texts
/// (each may be absent: mip, vots, whole rays). "reference" is mip on the grid; a contradicting renderer,
/// density on the grid or density with a slab throws vots::fit::InputError.
void applyProjection(FrameRequest& frame, std::optional<std::string_view> mode,
                     std::optional<std::string_view> renderer, std::optional<std::string_view> slab);

/// Why a size text is refused; the callers word the message.
enum class SizeProblem {
    None,
    NotWxH,          // no 'x'
    NotWholeNumbers, // a side is not an integer of at most 9 characters
    OutOfRange       // a side outside 1..maxSide (width and height hold the numbers read)
};

struct SizeParse {
    int width = 0;
    int height = 0;
    SizeProblem problem = SizeProblem::None;
};

/// Reads "WxH" (decimal integers, an optional '-', no '+' or spaces), each side in 1..maxSide.
SizeParse parseFrameSize(std::string_view text, int maxSide);
/// A decimal integer of at most 9 digits with nothing around it (a size side, a degree), or nullopt.
std::optional<int> parsePlainInt(std::string_view text);

/// The display window the frame gets: the request's, or one over `fullRange` in its colour map.
DisplaySettings displayFor(const FrameRequest& frame, std::array<float, 2> fullRange);

/// Draws the frame as RGBA with the renderer it names, which holds the data already: `grid` for
/// RendererKind::Grid, else `vots`. Without a window the frame shows the full range: of the
/// volume's samples (`volumeRange`, where the caller has the volume; else the Vot-Space's values), for
/// density the Vot renderer's density range. `abandoned`: RenderOptions::abandoned.
RgbaImage renderFrame(const FrameRequest& frame, VotRenderer* vots, GridRenderer* grid,
                      std::optional<std::array<float, 2>> volumeRange,
                      const std::function<bool()>& abandoned = {});

} // namespace vots::render
