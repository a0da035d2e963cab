// Turntable output of `vots render`: the -o pattern, folder checks, and all-or-nothing writes.
#include "TurntableOutput.h"

#include "vots/fit/AtomicFile.h"
#include "vots/fit/Error.h"
#include "vots/render/Png.h"
#include "vots/render/Turntable.h"
#include "vots/render/WebmWriter.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <future>
#include <optional>
#include <unistd.h>
#include <vector>

namespace vots::cli {
namespace {

struct Conversion {
    std::size_t begin = 0; // the '%'
    std::size_t end = 0;   // one past the 'd'
    int width = 0;         // 0: no padding
};

/// The one %d / %0Nd of a pattern, or nullopt when there is none, another '%', or a malformed one.
std::optional<Conversion> findConversion(const std::string& pattern) {
    if (std::count(pattern.begin(), pattern.end(), '%') != 1) return std::nullopt;
    Conversion c;
    c.begin = pattern.find('%');
    std::size_t i = c.begin + 1;
    if (i < pattern.size() && pattern[i] == '0') {
        ++i;
        if (i >= pattern.size() || pattern[i] < '1' || pattern[i] > '9') return std::nullopt;
        c.width = pattern[i] - '0';
        ++i;
    }
    if (i >= pattern.size() || pattern[i] != 'd') return std::nullopt;
    c.end = i + 1;
    return c;
}

} // namespace

bool isWebmPath(const std::string& path) {
    constexpr std::string_view EXTENSION = ".webm";
    if (path.size() < EXTENSION.size()) return false;
    return std::equal(EXTENSION.begin(), EXTENSION.end(), path.end() - EXTENSION.size(),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
}

namespace {

/// Frame files written to their temporary names; removed again unless committed.
class PendingFrames {
public:
    ~PendingFrames() {
        for (const auto& [temporary, path] : mFrames)
            std::remove(temporary.c_str());
    }
    void add(const std::string& path, const render::RgbaImage& image) {
        mFrames.emplace_back(fit::writeTemporaryFor(path, render::encodePng(image)), path);
    }
    void commit() {
        for (const auto& [temporary, path] : mFrames)
            fit::publishTemporary(temporary, path);
        mFrames.clear();
    }

private:
    std::vector<std::pair<std::string, std::string>> mFrames; // {temporary, final path}
};

} // namespace

TurntableOutput parseTurntableOutput(const std::string& output) {
    if (isWebmPath(output)) return {TurntableFormat::Webm, output};
    if (!findConversion(output))
        throw fit::InputError("-o '" + output +
                              "' with --turntable must end in .webm or name PNG frames with one %d or %0Nd "
                              "(e.g. frames/%03d.png) and no other '%'");
    return {TurntableFormat::PngFrames, output};
}

std::string framePath(const std::string& pattern, int index) {
    const auto c = findConversion(pattern);
    if (!c) throw std::invalid_argument("framePath: not a frame pattern");
    std::string number = std::to_string(index);
    if (number.size() < static_cast<std::size_t>(c->width))
        number.insert(0, static_cast<std::size_t>(c->width) - number.size(), '0');
    return pattern.substr(0, c->begin) + number + pattern.substr(c->end);
}

void checkOutputFolder(const std::string& path) {
    std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        throw fit::InputError("cannot write " + path + ": folder '" + folder.string() + "' does not exist");
    if (::access(folder.c_str(), W_OK) != 0)
        throw fit::InputError("cannot write " + path + ": folder '" + folder.string() + "' is not writable");
}

namespace {

/// Runs each frame's encoding and write on a second thread, one at a time and in frame order, while the
/// caller's GL thread draws the next frame: encoding a frame costs about as much as drawing it.
class OverlappedWrites {
public:
    ~OverlappedWrites() {
        // A draw that throws mid-turn still lets the frame in flight finish before the caller's
        // destructors remove the temporaries it may be writing.
        if (mInFlight.valid()) mInFlight.wait();
    }
    void push(std::function<void()> write) {
        if (mInFlight.valid()) mInFlight.get(); // rethrows the previous frame's error here
        mInFlight = std::async(std::launch::async, std::move(write));
    }
    void finish() {
        if (mInFlight.valid()) mInFlight.get();
    }

private:
    std::future<void> mInFlight;
};

} // namespace

struct TurntableWriter::State {
    TurntableOutput output;
    int frames = 0; // added so far
    std::optional<render::WebmWriter> video;
    PendingFrames pending;
    OverlappedWrites writes; // last, so a frame in flight ends before its temporary or the video goes
};

TurntableWriter::TurntableWriter(const TurntableOutput& output, int width, int height)
    : mState(std::make_unique<State>()) {
    mState->output = output;
    if (output.format == TurntableFormat::Webm) mState->video.emplace(width, height);
}

TurntableWriter::~TurntableWriter() = default;

void TurntableWriter::add(render::RgbaImage image) {
    State& s = *mState;
    const int index = s.frames++;
    if (s.video) {
        s.writes.push([&video = *s.video, image = std::move(image)] { video.addFrame(image); });
        return;
    }
    s.writes.push([&pending = s.pending, path = framePath(s.output.path, index), image = std::move(image)] {
        pending.add(path, image);
    });
}

void TurntableWriter::finish() {
    State& s = *mState;
    s.writes.finish();
    if (s.video)
        fit::writeFileAtomically(s.output.path, s.video->finish());
    else
        s.pending.commit();
}

void writeTurntable(const TurntableOutput& output, const render::FrameRequest& first, int frames,
                    std::optional<double> elevationDeg,
                    const std::function<render::RgbaImage(const render::FrameRequest&)>& draw) {
    TurntableWriter writer(output, first.width, first.height);
    for (int k = 0; k < frames; ++k)
        writer.add(draw(turntableFrame(first, frames, k, elevationDeg)));
    writer.finish();
}

render::FrameRequest turntableFrame(const render::FrameRequest& first, int frames, int index,
                                    std::optional<double> elevationDeg) {
    render::FrameRequest frame = first;
    frame.camera = render::turntableCamera(first.camera, frames, index, elevationDeg);
    return frame;
}

} // namespace vots::cli
