// Reading a --mode / mode= text: a render mode's name, or "reference" (mip on the grid renderer).
#include "vots/render/RenderMode.h"

#include "vots/fit/Error.h"

#include <string>

namespace vots::render {

ModeName parseModeName(std::string_view name) {
    if (name == "reference") return {RenderMode::Mip, RendererKind::Grid};
    if (const auto mode = fit::findNamed<RenderMode>(name)) return {*mode, std::nullopt};
    throw fit::InputError("unknown mode '" + std::string(name) + "' (known: " +
                          fit::knownNames<RenderMode>() + ", reference = mip on the grid renderer)");
}

} // namespace vots::render
