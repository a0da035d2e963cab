// WebmWriter: checks its arguments and hands the frames to the vots_webm module, loaded on first use.
#include "vots/render/WebmWriter.h"

#include "WebmModuleLoader.h"
#include "vots/fit/Error.h"

#include <stdexcept>
#include <string>

namespace vots::render {
namespace {

constexpr std::size_t ERROR_BYTES = 512;

} // namespace

struct WebmWriter::State {
    const WebmModule& module;
    VotsWebmEncoder* encoder = nullptr;
    int width = 0;
    int height = 0;
    bool finished = false;
    char error[ERROR_BYTES] = {};

    explicit State(const WebmModule& m) : module(m) {}
    ~State() { module.destroy(encoder); }
    State(const State&) = delete;
    State& operator=(const State&) = delete;

    void check(int failed) const {
        if (failed) throw std::runtime_error(error);
    }
};

WebmWriter::WebmWriter(int width, int height, int fps) {
    if (width < WEBM_MIN_SIDE || height < WEBM_MIN_SIDE)
        throw fit::InputError("a WebM animation needs frames of at least " + std::to_string(WEBM_MIN_SIDE) +
                              "x" + std::to_string(WEBM_MIN_SIDE) + " pixels");
    mState = std::make_unique<State>(webmModule());
    State& s = *mState;
    s.width = width;
    s.height = height;
    s.encoder = s.module.create(width, height, fps, s.error, sizeof s.error);
    if (!s.encoder) throw std::runtime_error(s.error);
}

WebmWriter::~WebmWriter() = default;

void WebmWriter::addFrame(const RgbaImage& image) {
    State& s = *mState;
    if (s.finished) throw std::logic_error("WebmWriter::addFrame after finish");
    if (image.width != s.width || image.height != s.height)
        throw std::invalid_argument("WebmWriter: frame size differs from the animation's");
    s.check(s.module.addFrame(s.encoder, image.pixels.data(), 4 * image.width, s.error, sizeof s.error));
}

std::vector<std::uint8_t> WebmWriter::finish() {
    State& s = *mState;
    if (s.finished) throw std::logic_error("WebmWriter::finish twice");
    s.finished = true;
    const std::uint8_t* bytes = nullptr;
    std::size_t size = 0;
    s.check(s.module.finish(s.encoder, &bytes, &size, s.error, sizeof s.error));
    return {bytes, bytes + size};
}

} // namespace vots::render
