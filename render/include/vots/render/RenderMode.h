// What an image shows: Vot MIP, Vot density, or the reference grid ray caster.
#pragma once

#include <string_view>

namespace vots::render {

enum class RenderMode {
    Mip,      // analytic maximum of each Vot's polynomial along the ray (VotRenderer)
    Density,  // log2 of the smallest Vot box along the ray, small = dark (VotRenderer)
    Reference // ray-marched trilinear grid MIP, step <= 0.5 voxel (GridRenderer)
};

std::string_view renderModeName(RenderMode mode); // "mip", "density", "reference"
/// Throws vots::fit::InputError listing the valid names.
RenderMode parseRenderMode(std::string_view name);

} // namespace vots::render
