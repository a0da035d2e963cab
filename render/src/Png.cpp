// PNG encoding through stb_image_write, its deflate done by libdeflate, and atomic writes.
//
// Encoding is on the server's critical path (with stb's defaults it took a large part of a frame's
// time), so: no alpha channel (always opaque), one grey channel when every pixel is grey, and the "up"
// filter instead of stb's per-row trial of five filters. stb's deflate is written for brevity, not speed
// (its header says so); libdeflate, already linked for CRC-32, compresses the same rows faster and
// smaller (bench/RESULTS.md, "PNG encoding", has the figures).
#include "vots/render/Png.h"

#include "OpaqueChannels.h"

#include "vots/fit/AtomicFile.h"
#include "vots/fit/Error.h"

#include <libdeflate.h>

#include <cstdlib>
#include <memory>

namespace {
// stb_image_write's hook for a zlib stream; stb frees the result with free().
unsigned char* deflateForStb(unsigned char* data, int length, int* outLength, int /*stbQuality*/) {
    constexpr int LEVEL = 4; // the knee of size against time on CT frames (bench/RESULTS.md)
    thread_local std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
        libdeflate_alloc_compressor(LEVEL), &libdeflate_free_compressor);
    if (!compressor || length < 0) return nullptr;
    const std::size_t bound =
        libdeflate_zlib_compress_bound(compressor.get(), static_cast<std::size_t>(length));
    auto* out = static_cast<unsigned char*>(std::malloc(bound));
    if (!out) return nullptr;
    const std::size_t written =
        libdeflate_zlib_compress(compressor.get(), data, static_cast<std::size_t>(length), out, bound);
    if (written == 0) {
        std::free(out);
        return nullptr;
    }
    *outLength = static_cast<int>(written);
    return out;
}
} // namespace

// The implementation is compiled here, private to this file, so that it can use deflateForStb.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBIW_ZLIB_COMPRESS deflateForStb
#include <stb/stb_image_write.h>

#include <mutex>

namespace vots::render {

namespace {
void appendBytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}
constexpr int PNG_FILTER_UP = 2;

// stb's settings are globals (this file's own copies); set once, before the first encode.
void configureStb() {
    static std::once_flag once;
    std::call_once(once, [] { stbi_write_force_png_filter = PNG_FILTER_UP; });
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
    fit::writeFileAtomically(path, encodePng(image));
}

} // namespace vots::render
