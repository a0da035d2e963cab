// The vots_webm module: RGBA -> yuv420p (libswscale) -> VP9 (libvpx through libavcodec) -> WebM
// (libavformat), in memory, behind the C interface of WebmModule.h. Only this file links FFmpeg.
#include "WebmModule.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// Constant quality: the bit rate follows the picture. 20 keeps bone edges in a 512^2 MIP crisp.
constexpr const char* VP9_CRF = "20";
constexpr std::size_t IO_BUFFER_BYTES = 1 << 16;

std::string avError(int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(code, text, sizeof text);
    return text;
}

void check(int code, const char* what) {
    if (code < 0) throw std::runtime_error(std::string("WebM encoding: ") + what + ": " + avError(code));
}

// FFmpeg's default log level prints an info line per encoder opened, on the command's stderr, where
// the CLI promises only its own messages. Set once, when the module is loaded.
[[gnu::constructor]] void quietFfmpegLogs() {
    av_log_set_level(AV_LOG_ERROR);
}

// FFmpeg 6.1 (libavformat 61) made the write callback's buffer const.
#if LIBAVFORMAT_VERSION_MAJOR >= 61
using WriteBuffer = const std::uint8_t*;
#else
using WriteBuffer = std::uint8_t*;
#endif

/// A seekable in-memory file: the WebM muxer seeks back to write the duration and the cues' position.
struct MemoryFile {
    std::vector<std::uint8_t> bytes;
    std::size_t position = 0;

    static int write(void* opaque, WriteBuffer data, int size) {
        auto* f = static_cast<MemoryFile*>(opaque);
        const auto n = static_cast<std::size_t>(size);
        if (f->position + n > f->bytes.size()) f->bytes.resize(f->position + n);
        std::memcpy(f->bytes.data() + f->position, data, n);
        f->position += n;
        return size;
    }
    static std::int64_t seek(void* opaque, std::int64_t offset, int whence) {
        auto* f = static_cast<MemoryFile*>(opaque);
        const auto size = static_cast<std::int64_t>(f->bytes.size());
        if (whence & AVSEEK_SIZE) return size;
        std::int64_t base = 0;
        switch (whence & ~AVSEEK_FORCE) {
        case SEEK_SET:
            base = 0;
            break;
        case SEEK_CUR:
            base = static_cast<std::int64_t>(f->position);
            break;
        case SEEK_END:
            base = size;
            break;
        default:
            return AVERROR(EINVAL);
        }
        if (base + offset < 0) return AVERROR(EINVAL);
        f->position = static_cast<std::size_t>(base + offset);
        return base + offset;
    }
};

} // namespace

/// One animation being encoded: FFmpeg's contexts and the file they write.
struct VotsWebmEncoder {
    int width = 0;
    int height = 0;
    std::int64_t nextPts = 0;
    MemoryFile file;
    AVFormatContext* format = nullptr;
    AVIOContext* io = nullptr;
    AVCodecContext* codec = nullptr;
    AVStream* stream = nullptr;
    SwsContext* scaler = nullptr;
    AVFrame* frame = nullptr;
    AVPacket* packet = nullptr;

    ~VotsWebmEncoder() {
        av_packet_free(&packet);
        av_frame_free(&frame);
        sws_freeContext(scaler);
        avcodec_free_context(&codec);
        if (format) avformat_free_context(format);
        if (io) av_freep(&io->buffer);
        avio_context_free(&io);
    }

    /// Opens the encoder and the muxer and writes the header; what it opened before a throw, the
    /// destructor frees.
    void open(int w, int h, int fps);

    /// Sends `input` (nullptr: flush) and muxes every packet the encoder has ready.
    void encode(const AVFrame* input) {
        check(avcodec_send_frame(codec, input), "send frame");
        for (;;) {
            const int got = avcodec_receive_packet(codec, packet);
            if (got == AVERROR(EAGAIN) || got == AVERROR_EOF) return;
            check(got, "receive packet");
            av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            check(av_interleaved_write_frame(format, packet), "write packet");
        }
    }
};

void VotsWebmEncoder::open(int w, int h, int fps) {
    VotsWebmEncoder& s = *this;
    s.width = w;
    s.height = h;
    const AVCodec* vp9 = avcodec_find_encoder_by_name("libvpx-vp9");
    if (!vp9) throw std::runtime_error("WebM encoding: this FFmpeg has no libvpx-vp9 encoder");

    check(avformat_alloc_output_context2(&s.format, nullptr, "webm", nullptr), "open the WebM muxer");
    s.format->flags |= AVFMT_FLAG_BITEXACT; // no library version or random ids in the header
    auto* buffer = static_cast<unsigned char*>(av_malloc(IO_BUFFER_BYTES));
    if (!buffer) throw std::bad_alloc();
    s.io = avio_alloc_context(buffer, static_cast<int>(IO_BUFFER_BYTES), 1, &s.file, nullptr,
                              &MemoryFile::write, &MemoryFile::seek);
    if (!s.io) {
        av_free(buffer);
        throw std::bad_alloc();
    }
    s.format->pb = s.io;
    s.format->flags |= AVFMT_FLAG_CUSTOM_IO;

    s.codec = avcodec_alloc_context3(vp9);
    if (!s.codec) throw std::bad_alloc();
    s.codec->width = width;
    s.codec->height = height;
    s.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    // What libswscale's RGB -> YUV conversion produces by default (BT.601, limited range), said in the
    // file so that players do not guess another matrix for the colour maps.
    s.codec->colorspace = AVCOL_SPC_SMPTE170M;
    s.codec->color_primaries = AVCOL_PRI_SMPTE170M;
    s.codec->color_trc = AVCOL_TRC_SMPTE170M;
    s.codec->color_range = AVCOL_RANGE_MPEG;
    s.codec->time_base = AVRational{1, fps};
    s.codec->framerate = AVRational{fps, 1};
    s.codec->gop_size = fps;   // a key frame each second: seeking in the turn stays cheap
    s.codec->bit_rate = 0;     // with crf: constant quality, no bit-rate cap
    s.codec->thread_count = 1; // libvpx's threads may split the work differently run to run
    s.codec->flags |= AV_CODEC_FLAG_BITEXACT;
    if (s.format->oformat->flags & AVFMT_GLOBALHEADER) s.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    check(av_opt_set(s.codec->priv_data, "crf", VP9_CRF, 0), "set crf");
    // The fastest settings: a turn's encoding should cost little next to drawing its frames.
    check(av_opt_set(s.codec->priv_data, "deadline", "realtime", 0), "set deadline");
    check(av_opt_set(s.codec->priv_data, "cpu-used", "8", 0), "set speed");
    check(av_opt_set(s.codec->priv_data, "row-mt", "0", 0), "set row-mt");
    check(avcodec_open2(s.codec, vp9, nullptr), "open the VP9 encoder");

    s.stream = avformat_new_stream(s.format, nullptr);
    if (!s.stream) throw std::bad_alloc();
    s.stream->time_base = s.codec->time_base;
    check(avcodec_parameters_from_context(s.stream->codecpar, s.codec), "stream parameters");
    check(avformat_write_header(s.format, nullptr), "write the WebM header");

    s.scaler = sws_getContext(width, height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_YUV420P,
                              SWS_BICUBIC | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr, nullptr, nullptr);
    s.frame = av_frame_alloc();
    s.packet = av_packet_alloc();
    if (!s.scaler || !s.frame || !s.packet) throw std::bad_alloc();
    s.frame->format = AV_PIX_FMT_YUV420P;
    s.frame->width = width;
    s.frame->height = height;
    check(av_frame_get_buffer(s.frame, 0), "frame buffer");
}

namespace {

/// Runs `body`, turning any exception into `error` and a nonzero result: none may cross the C interface.
template <typename Body> int guarded(char* error, std::size_t errorSize, Body&& body) {
    try {
        body();
        return 0;
    } catch (const std::bad_alloc&) {
        std::snprintf(error, errorSize, "WebM encoding: out of memory");
    } catch (const std::exception& e) {
        std::snprintf(error, errorSize, "%s", e.what());
    } catch (...) {
        std::snprintf(error, errorSize, "WebM encoding: unknown failure");
    }
    return 1;
}

} // namespace

extern "C" {

int vots_webm_abi_version(void) {
    return VOTS_WEBM_ABI_VERSION;
}

VotsWebmEncoder* vots_webm_create(int width, int height, int fps, char* error, size_t errorSize) {
    VotsWebmEncoder* encoder = nullptr;
    guarded(error, errorSize, [&] {
        auto opened = std::make_unique<VotsWebmEncoder>();
        opened->open(width, height, fps);
        encoder = opened.release();
    });
    return encoder;
}

int vots_webm_add_frame(VotsWebmEncoder* encoder, const uint8_t* rgba, int stride, char* error,
                        size_t errorSize) {
    return guarded(error, errorSize, [&] {
        VotsWebmEncoder& s = *encoder;
        check(av_frame_make_writable(s.frame), "frame writable");
        const std::uint8_t* const source[1] = {rgba};
        const int sourceStride[1] = {stride};
        sws_scale(s.scaler, source, sourceStride, 0, s.height, s.frame->data, s.frame->linesize);
        s.frame->pts = s.nextPts++;
        s.encode(s.frame);
    });
}

int vots_webm_finish(VotsWebmEncoder* encoder, const uint8_t** bytes, size_t* size, char* error,
                     size_t errorSize) {
    return guarded(error, errorSize, [&] {
        VotsWebmEncoder& s = *encoder;
        s.encode(nullptr);
        check(av_write_trailer(s.format), "write the WebM trailer");
        avio_flush(s.io);
        *bytes = s.file.bytes.data();
        *size = s.file.bytes.size();
    });
}

void vots_webm_destroy(VotsWebmEncoder* encoder) {
    delete encoder;
}

} // extern "C"
