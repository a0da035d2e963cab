// What an image shows (MIP, MinIP, average, Vot density) and which renderer draws it (Vots or the grid).
#pragma once

#include "vots/fit/EnumNames.h"

#include <optional>
#include <string_view>

namespace vots::render {

enum class RenderMode {
    Mip,    // maximum along each ray
    MinIp,  // minimum along each ray; uncovered (background) cells count as the background value
    Aip,    // average along each ray: the integral over its path in the volume (or slab) / the path length
    Density // log2 of the smallest Vot box along the ray, small = dark (Vots only)
};

enum class RendererKind {
    Vots, // analytic, from the Vot-Space (VotRenderer)
    Grid  // exact over the trilinear interpolant of the samples (GridRenderer): the ground truth
};

inline constexpr auto RENDER_MODE_NAMES =
    fit::nameTable<RenderMode>("mode", {{RenderMode::Mip, "mip"},
                                        {RenderMode::MinIp, "minip"},
                                        {RenderMode::Aip, "aip"},
                                        {RenderMode::Density, "density"}});
constexpr const auto& namesOf(RenderMode) {
    return RENDER_MODE_NAMES;
}
inline constexpr auto RENDERER_NAMES =
    fit::nameTable<RendererKind>("renderer", {{RendererKind::Vots, "vots"}, {RendererKind::Grid, "grid"}});
constexpr const auto& namesOf(RendererKind) {
    return RENDERER_NAMES;
}

constexpr std::string_view renderModeName(RenderMode mode) {
    return fit::nameOf(mode);
}
constexpr std::string_view rendererName(RendererKind kind) {
    return fit::nameOf(kind);
}

/// A --mode / mode= text read: a projection, and for "reference" (kept from before the grid renderer
/// drew every mode) also the renderer it implies, mip on the grid.
struct ModeName {
    RenderMode mode = RenderMode::Mip;
    std::optional<RendererKind> impliedRenderer;
};
/// Throws vots::fit::InputError listing the valid names.
ModeName parseModeName(std::string_view name);
/// Throws vots::fit::InputError listing the valid names.
inline RendererKind parseRendererName(std::string_view name) {
    return fit::parseName<RendererKind>(name);
}

} // namespace vots::render
