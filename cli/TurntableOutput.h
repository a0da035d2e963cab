// Where `vots render --turntable N` writes: numbered PNG frames from a %d pattern, or one WebM file.
#pragma once

#include "vots/render/FrameRequest.h"
#include "vots/render/Image.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace vots::cli {

enum class TurntableFormat { PngFrames, Webm };

struct TurntableOutput {
    TurntableFormat format = TurntableFormat::PngFrames;
    std::string path; // the file (Webm) or the pattern with one %d, %0Nd (PngFrames)
};

/// True when path ends in .webm, in any case.
bool isWebmPath(const std::string& path);

/// "-o turn.webm" (any case of the extension) is a WebM video; anything else must hold exactly one
/// %d or %0Nd (N = 1..9) and no other '%', and names PNG frames. Throws vots::fit::InputError.
TurntableOutput parseTurntableOutput(const std::string& output);

/// The pattern with its conversion replaced by index (zero-padded to the pattern's width).
std::string framePath(const std::string& pattern, int index);

/// Throws vots::fit::InputError unless the folder that would hold path exists (and, for a user other
/// than root, is writable), so that a bad -o fails before the load and the fit.
void checkOutputFolder(const std::string& path);

/// Frame `index` of a turn of `frames` from `first`: its camera turned (render::turntableCamera).
render::FrameRequest turntableFrame(const render::FrameRequest& first, int frames, int index,
                                    std::optional<double> elevationDeg);

/// Writes a turn's frames in the order they are added: PNG frames to temporary files, renamed only by
/// finish(); a WebM written at once by finish(). Each frame is encoded and written on a second thread
/// while the caller draws the next; a write's error comes out of the next add() or finish(). Destroyed
/// without finish() (an error on the way), it leaves no frame and no temporary file behind.
class TurntableWriter {
public:
    TurntableWriter(const TurntableOutput& output, int width, int height);
    ~TurntableWriter();
    TurntableWriter(const TurntableWriter&) = delete;
    TurntableWriter& operator=(const TurntableWriter&) = delete;
    void add(render::RgbaImage image);
    void finish();

private:
    struct State;
    std::unique_ptr<State> mState;
};

/// Draws the turn's frames (turntableCamera of `first`) with `draw` and writes them. PNG frames go to
/// temporary files first and are renamed only after every frame is drawn and written, a WebM is
/// written at once at the end: an error leaves no frame and no temporary file behind.
void writeTurntable(const TurntableOutput& output, const render::FrameRequest& first, int frames,
                    std::optional<double> elevationDeg,
                    const std::function<render::RgbaImage(const render::FrameRequest&)>& draw);

} // namespace vots::cli
