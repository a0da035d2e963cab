// Names of the render modes for the command line and the server.
#include "vots/render/RenderMode.h"

#include "vots/fit/Error.h"

#include <string>

namespace vots::render {

std::string_view renderModeName(RenderMode mode) {
    switch (mode) {
    case RenderMode::Mip:
        return "mip";
    case RenderMode::Density:
        return "density";
    case RenderMode::Reference:
        return "reference";
    }
    return "mip";
}

RenderMode parseRenderMode(std::string_view name) {
    for (RenderMode m : {RenderMode::Mip, RenderMode::Density, RenderMode::Reference})
        if (name == renderModeName(m)) return m;
    throw fit::InputError("unknown mode '" + std::string(name) + "' (known: mip, density, reference)");
}

} // namespace vots::render
