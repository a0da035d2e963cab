// JPEG through libjpeg-turbo's libjpeg API: memory in, memory out, errors as fit::InputError.
//
// libjpeg reports a failure by calling error_exit, which must not return. Unwinding a C++ exception
// through libjpeg's C frames is undefined, so error_exit longjmps back to the one frame that called
// into libjpeg; that frame holds no object with a destructor between the setjmp and the calls.
#include "vots/render/Jpeg.h"

#include "OpaqueChannels.h"
#include "vots/fit/Error.h"

#include <cstdio> // jpeglib.h needs FILE
#include <jpeglib.h>

#include <csetjmp>
#include <cstdlib>
#include <string>

namespace vots::render {
namespace {

struct ErrorJump {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void jumpOnError(j_common_ptr info) {
    auto* error = reinterpret_cast<ErrorJump*>(info->err);
    (*info->err->format_message)(info, error->message);
    std::longjmp(error->jump, 1);
}

// Returns false with error.message set when libjpeg failed; *out is malloc'ed by libjpeg.
bool compress(const std::uint8_t* pixels, int width, int height, int channels, int quality, ErrorJump& error,
              unsigned char** out, unsigned long* size) {
    jpeg_compress_struct info{};
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jumpOnError;
    if (setjmp(error.jump)) {
        jpeg_destroy_compress(&info);
        return false;
    }
    jpeg_create_compress(&info);
    jpeg_mem_dest(&info, out, size);
    info.image_width = static_cast<JDIMENSION>(width);
    info.image_height = static_cast<JDIMENSION>(height);
    info.input_components = channels;
    info.in_color_space = channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&info);
    info.dct_method = JDCT_ISLOW; // turbo's SIMD ISLOW is as fast as IFAST and more exact
    jpeg_set_quality(&info, quality, TRUE);
    jpeg_start_compress(&info, TRUE);
    const auto stride = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = const_cast<JSAMPROW>(pixels + info.next_scanline * stride);
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    return true;
}

bool decompress(const std::vector<std::uint8_t>& jpeg, ErrorJump& error, RgbaImage& image) {
    jpeg_decompress_struct info{};
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jumpOnError;
    if (setjmp(error.jump)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, jpeg.data(), static_cast<unsigned long>(jpeg.size()));
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_EXT_RGBA; // libjpeg-turbo's extension: alpha filled with 255
    jpeg_start_decompress(&info);
    image.width = static_cast<int>(info.output_width);
    image.height = static_cast<int>(info.output_height);
    image.pixels.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4);
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = image.pixels.data() + static_cast<std::size_t>(info.output_scanline) *
                                                 static_cast<std::size_t>(image.width) * 4;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    return true;
}

} // namespace

std::vector<std::uint8_t> encodeJpeg(const RgbaImage& image, int quality) {
    checkImageSize(image.width, image.height);
    if (quality < 1 || quality > 100) throw fit::InputError("JPEG quality must be 1..100");
    int channels = 0;
    const std::vector<std::uint8_t> pixels = opaqueChannels(image, channels);
    ErrorJump error{};
    unsigned char* out = nullptr;
    unsigned long size = 0;
    const bool ok = compress(pixels.data(), image.width, image.height, channels, quality, error, &out, &size);
    std::vector<std::uint8_t> bytes;
    if (ok) bytes.assign(out, out + size);
    std::free(out);
    if (!ok) throw fit::InputError(std::string("JPEG encoding failed: ") + error.message);
    return bytes;
}

RgbaImage decodeJpeg(const std::vector<std::uint8_t>& jpeg) {
    if (jpeg.empty()) throw fit::InputError("JPEG decoding failed: no bytes");
    ErrorJump error{};
    RgbaImage image;
    if (!decompress(jpeg, error, image))
        throw fit::InputError(std::string("JPEG decoding failed: ") + error.message);
    return image;
}

} // namespace vots::render
