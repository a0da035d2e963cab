// PNG encoding through stb_image_write (implementation lives in Debian's libstb.so) and atomic writes.
//
// Encoding is on the server's critical path (a 512x512 frame took 21 ms with stb's defaults, a quarter of
// the frame budget), so: no alpha channel (always opaque), one grey channel when every pixel is grey,
// and the "up" filter at compression level 4 instead of stb's per-row trial of five filters at level 8.
// Measured on a CT frame (bench/RESULTS.md): RGBA 20.8 ms / 63 KB -> RGB 12 ms / 62 KB -> grey 4 ms / 35 KB.
#include "vots/render/Png.h"

#include "vots/fit/Error.h"

#include <stb/stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <mutex>
#include <unistd.h>

namespace vots::render {

namespace {
void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}
constexpr int PNG_FILTER_UP = 2;
constexpr int PNG_COMPRESSION_LEVEL = 4;

// stb's settings are process-wide globals in libstb.so; set once, before the first encode.
void configureStb() {
    static std::once_flag once;
    std::call_once(once, [] {
        stbi_write_force_png_filter = PNG_FILTER_UP;
        stbi_write_png_compression_level = PNG_COMPRESSION_LEVEL;
    });
}

// The pixels as grey (one channel) when r == g == b everywhere, else as RGB.
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

} // namespace

std::vector<std::uint8_t> encodePng(const RgbaImage& image) {
    checkImageSize(image.width, image.height);
    configureStb();
    int channels = 0;
    const std::vector<std::uint8_t> pixels = opaqueChannels(image, channels);
    std::vector<std::uint8_t> out;
    if (!stbi_write_png_to_func(appendBytes, &out, image.width, image.height, channels, pixels.data(),
                                image.width * channels))
        throw fit::InputError("PNG encoding failed");
    return out;
}

void writePng(const std::string& path, const RgbaImage& image) {
    const std::vector<std::uint8_t> bytes = encodePng(image);
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw fit::InputError("cannot write " + path);
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    if (std::fclose(f) != 0 || !ok) {
        std::remove(tmp.c_str());
        throw fit::InputError("cannot write " + path);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw fit::InputError("cannot write " + path + ": " + ec.message());
    }
}

} // namespace vots::render
