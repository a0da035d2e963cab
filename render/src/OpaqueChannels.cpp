// opaqueChannels: RGBA to grey or RGB rows, shared by the PNG and JPEG encoders.
#include "OpaqueChannels.h"

namespace vots::render {

std::vector<std::uint8_t> opaqueChannels(const RgbaImage& image, int& channels) {
    const std::vector<std::uint8_t>& rgba = image.pixels;
    bool grey = true;
    for (std::size_t i = 0; grey && i < rgba.size(); i += 4)
        grey = rgba[i] == rgba[i + 1] && rgba[i] == rgba[i + 2];
    channels = grey ? 1 : 3;
    std::vector<std::uint8_t> out;
    out.reserve(rgba.size() / 4 * static_cast<std::size_t>(channels));
    for (std::size_t i = 0; i < rgba.size(); i += 4)
        out.insert(out.end(), rgba.begin() + static_cast<std::ptrdiff_t>(i),
                   rgba.begin() + static_cast<std::ptrdiff_t>(i) + channels);
    return out;
}

} // namespace vots::render
