// PNG encoding through stb_image_write (implementation lives in Debian's libstb.so) and atomic writes.
#include "vots/render/Png.h"

#include "vots/fit/Error.h"

#include <stb/stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace vots::render {

namespace {
void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}
} // namespace

std::vector<std::uint8_t> encodePng(const RgbaImage& image) {
    checkImageSize(image.width, image.height);
    std::vector<std::uint8_t> out;
    if (!stbi_write_png_to_func(appendBytes, &out, image.width, image.height, 4, image.pixels.data(),
                                image.width * 4))
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
