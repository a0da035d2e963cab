// Decodes a video file with FFmpeg's libraries in a test: how many frames, of what size, in what container.
#pragma once

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <string>

namespace vots::test {

struct VideoProbe {
    bool opened = false;
    std::string container; // libavformat's name of the demuxer ("matroska,webm")
    std::string codec;     // "vp9"
    int width = 0;
    int height = 0;
    int framesDecoded = 0; // frames the decoder gave back, all packets read and the decoder drained
    std::string error;     // why it stopped early, empty when the whole file decoded
};

/// Opens path, decodes every frame of its first video stream and reports what it saw.
inline VideoProbe probeVideo(const std::string& path) {
    VideoProbe probe;
    AVFormatContext* format = nullptr;
    if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) {
        probe.error = "cannot open";
        return probe;
    }
    probe.opened = true;
    probe.container = format->iformat->name;
    AVCodecContext* codec = nullptr;
    AVPacket* packet = av_packet_alloc();
    AVFrame* frame = av_frame_alloc();
    const AVCodec* decoder = nullptr;
    const int stream = avformat_find_stream_info(format, nullptr) < 0
                           ? -1
                           : av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
    if (stream < 0 || !decoder) {
        probe.error = "no video stream";
    } else {
        probe.codec = avcodec_get_name(format->streams[stream]->codecpar->codec_id);
        codec = avcodec_alloc_context3(decoder);
        avcodec_parameters_to_context(codec, format->streams[stream]->codecpar);
        if (avcodec_open2(codec, decoder, nullptr) < 0) probe.error = "cannot open the decoder";
        const auto drain = [&] {
            while (avcodec_receive_frame(codec, frame) == 0) {
                ++probe.framesDecoded;
                probe.width = frame->width;
                probe.height = frame->height;
            }
        };
        while (probe.error.empty() && av_read_frame(format, packet) >= 0) {
            if (packet->stream_index == stream) {
                if (avcodec_send_packet(codec, packet) < 0) probe.error = "bad packet";
                drain();
            }
            av_packet_unref(packet);
        }
        if (probe.error.empty()) {
            avcodec_send_packet(codec, nullptr);
            drain();
        }
    }
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
    return probe;
}

} // namespace vots::test
