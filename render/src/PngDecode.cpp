// decodePng through stb_image, PNG only: the server re-reads cached frames to put them into a turntable.
#include "vots/render/Png.h"

#include "vots/fit/Error.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include <climits>
#include <memory>

namespace vots::render {

RgbaImage decodePng(const std::vector<std::uint8_t>& png) {
    if (png.size() > static_cast<std::size_t>(INT_MAX)) throw fit::InputError("PNG too large to decode");
    int width = 0, height = 0, channels = 0;
    constexpr int RGBA = 4;
    std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> pixels(
        stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &width, &height, &channels, RGBA),
        &stbi_image_free);
    if (!pixels) throw fit::InputError(std::string("not a PNG: ") + stbi_failure_reason());
    checkImageSize(width, height);
    RgbaImage image;
    image.width = width;
    image.height = height;
    const std::size_t bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * RGBA;
    image.pixels.assign(pixels.get(), pixels.get() + bytes);
    return image;
}

} // namespace vots::render
