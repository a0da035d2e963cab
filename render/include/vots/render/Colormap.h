// Colour maps for the display pass (grey, bone, hot, viridis-like), as 256-entry RGBA8 tables.
#pragma once

#include "vots/fit/EnumNames.h"

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

inline constexpr auto COLORMAP_NAMES = fit::nameTable<Colormap>("colormap", {{Colormap::Grey, "grey"},
                                                                             {Colormap::Bone, "bone"},
                                                                             {Colormap::Hot, "hot"},
                                                                             {Colormap::Viridis, "viridis"},
                                                                             {Colormap::Grey, "gray"}});
constexpr const auto& namesOf(Colormap) {
    return COLORMAP_NAMES;
}

/// "grey", "bone", "hot", "viridis".
constexpr std::string_view colormapName(Colormap map) {
    return fit::nameOf(map);
}
/// Accepts the names above (and "gray"); throws vots::fit::InputError listing the valid names.
inline Colormap parseColormap(std::string_view name) {
    return fit::parseName<Colormap>(name);
}
/// The table, built once on first use.
const ColormapTable& colormapTable(Colormap map);

} // namespace vots::render
