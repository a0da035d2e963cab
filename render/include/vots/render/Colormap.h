// Colour maps for the display pass (grey, bone, hot, viridis-like), as 256-entry RGBA8 tables.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace vots::render {

enum class Colormap {
    Grey,   // black -> white
    Bone,   // grey with a blue-white tint, like MATLAB "bone" (built from anchors, not copied)
    Hot,    // black -> red -> yellow -> white
    Viridis // perceptually uniform dark blue -> green -> yellow (our own polynomial fit, see Colormap.cpp)
};

inline constexpr std::array<Colormap, 4> ALL_COLORMAPS{Colormap::Grey, Colormap::Bone, Colormap::Hot,
                                                       Colormap::Viridis};

using ColormapTable = std::array<std::array<std::uint8_t, 4>, 256>; // RGBA8, entry 0 = window low end

/// "grey", "bone", "hot", "viridis".
std::string_view colormapName(Colormap map);
/// Accepts the names above (and "gray"); throws vots::fit::InputError listing the valid names.
Colormap parseColormap(std::string_view name);
/// The table, built once on first use.
const ColormapTable& colormapTable(Colormap map);

} // namespace vots::render
