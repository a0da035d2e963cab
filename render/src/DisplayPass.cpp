// The display pass: window/level and colour map from a float frame to RGBA8, on the CPU.
//
// On the CPU for every renderer, GPU or llvmpipe: a frame drawn on the CPU (the splat) no longer goes up to
// the GL and back for it, and one drawn on the GL is read back as R32F, the same bytes as RGBA8. A pass of
// a table lookup per pixel, on every core, costs less at a megapixel than llvmpipe's shader took
// (bench/RESULTS.md, "The display pass on the CPU").
#include "vots/render/DisplayPass.h"

#include "ParallelChunks.h"

#include "vots/fit/Error.h"

#include <cstring>

namespace vots::render {

RgbaImage applyDisplay(const FloatImage& image, const DisplaySettings& display) {
    checkImageSize(image.width, image.height);
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
        throw fit::GraphicsError("float image has the wrong number of pixels");
    if (!(display.width > 0.f)) throw fit::GraphicsError("display window width must be > 0");
    const ColormapTable& table = colormapTable(display.colormap);
    RgbaImage out;
    out.width = image.width;
    out.height = image.height;
    out.pixels.resize(image.pixels.size() * 4);
    parallelChunks(image.pixels.size(), [&](std::size_t first, std::size_t last) {
        for (std::size_t i = first; i < last; ++i)
            std::memcpy(&out.pixels[4 * i],
                        table[static_cast<std::size_t>(displayIndex(image.pixels[i], display))].data(), 4);
    });
    return out;
}

} // namespace vots::render
