// A turntable as a video: RGBA frames -> VP9 in WebM through FFmpeg's libraries, reproducibly.
#pragma once

#include "vots/render/Image.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace vots::render {

/// Frames per second of every animation Vots writes: a 36-frame turn lasts three seconds.
inline constexpr int ANIMATION_FPS = 12;
/// Smallest frame side a WebM animation takes: 4:2:0 chroma halves each side.
inline constexpr int WEBM_MIN_SIDE = 2;

/// VP9 (libvpx) in WebM: it plays in every browser the viewer supports, and VP9 keeps the fine grey
/// levels of a MIP better than VP8 at the same size. The encoder runs single-threaded with fixed settings
/// and both libavcodec and libavformat in bit-exact mode, so the same frames give the same bytes with
/// the same libraries (docs/DESIGN.md, "Turntables"). Not thread-safe; one writer per animation.
class WebmWriter {
public:
    /// Loads the FFmpeg module on first use (render/src/WebmModuleLoader.h). Throws vots::fit::InputError
    /// for a size the encoder refuses, std::runtime_error when the module does not load, or FFmpeg lacks
    /// the VP9 encoder or fails.
    WebmWriter(int width, int height, int fps = ANIMATION_FPS);
    ~WebmWriter();
    WebmWriter(const WebmWriter&) = delete;
    WebmWriter& operator=(const WebmWriter&) = delete;

    /// Encodes one frame; it must have the size given to the constructor.
    void addFrame(const RgbaImage& frame);
    /// Flushes the encoder and returns the whole file. The writer is spent afterwards.
    std::vector<std::uint8_t> finish();

private:
    struct State;
    std::unique_ptr<State> mState;
};

} // namespace vots::render
