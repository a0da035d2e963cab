// Names of the render modes and renderers for the command line and the server.
#include "vots/render/RenderMode.h"

#include "vots/fit/Error.h"

#include <string>

namespace vots::render {

std::string_view renderModeName(RenderMode mode) {
    switch (mode) {
    case RenderMode::Mip:
        return "mip";
    case RenderMode::MinIp:
        return "minip";
    case RenderMode::Aip:
        return "aip";
    case RenderMode::Density:
        return "density";
    }
    return "mip";
}

std::string_view rendererName(RendererKind kind) {
    return kind == RendererKind::Grid ? "grid" : "vots";
}

ModeName parseModeName(std::string_view name) {
    if (name == "reference") return {RenderMode::Mip, RendererKind::Grid};
    for (RenderMode m : {RenderMode::Mip, RenderMode::MinIp, RenderMode::Aip, RenderMode::Density})
        if (name == renderModeName(m)) return {m, std::nullopt};
    throw fit::InputError("unknown mode '" + std::string(name) +
                          "' (known: mip, minip, aip, density, reference = mip on the grid renderer)");
}

RendererKind parseRendererName(std::string_view name) {
    for (RendererKind k : {RendererKind::Vots, RendererKind::Grid})
        if (name == rendererName(k)) return k;
    throw fit::InputError("unknown renderer '" + std::string(name) + "' (known: vots, grid)");
}

} // namespace vots::render
