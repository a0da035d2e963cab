// `vots render`'s arguments: checks of every option before anything is read, and the render's fit.
#include "RenderArgs.h"

#include "Args.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/render/CameraText.h"
#include "vots/render/Turntable.h"
#include "vots/render/WebmWriter.h"

#include <fstream>
#include <tuple>

namespace vots::cli {

std::string sizeText(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

namespace {

/// The turntable's options, checked with the output folders before any load or fit.
std::optional<TurntableOutput> checkTurntableArgs(const RenderArgs& a, const render::FrameRequest& first) {
    if (!a.turntable) {
        if (a.elevation) throw fit::InputError("--elevation is for --turntable N");
        if (isWebmPath(a.output))
            throw fit::InputError("-o " + a.output + ": a WebM animation needs --turntable N");
        checkOutputFolder(a.output);
        return std::nullopt;
    }
    const int frames = *a.turntable;
    if (frames < 1 || frames > render::MAX_TURNTABLE_FRAMES)
        throw fit::InputError("--turntable " + std::to_string(frames) + " is outside 1.." +
                              std::to_string(render::MAX_TURNTABLE_FRAMES) + " frames");
    render::validateCamera(render::turntableCamera(first.camera, frames, 0, a.elevation));
    const TurntableOutput output = parseTurntableOutput(a.output);
    if (output.format == TurntableFormat::Webm) {
        if (first.width < render::WEBM_MIN_SIDE || first.height < render::WEBM_MIN_SIDE)
            throw fit::InputError("--size " + a.size + " is too small for a WebM animation (at least " +
                                  std::to_string(render::WEBM_MIN_SIDE) + " per side)");
        checkOutputFolder(output.path);
    } else {
        for (int k = 0; k < frames; ++k)
            checkOutputFolder(framePath(output.path, k));
    }
    return output;
}

std::pair<int, int> parseSize(const std::string& text) {
    const render::SizeParse size = render::parseFrameSize(text, render::MAX_IMAGE_SIDE);
    if (size.problem != render::SizeProblem::None)
        throw fit::InputError("--size '" + text +
                              "' is not WxH with 1 <= W, H <= " + std::to_string(render::MAX_IMAGE_SIDE));
    return {size.width, size.height};
}

} // namespace

CheckedArgs checkArgs(const RenderArgs& a) {
    CheckedArgs c;
    render::FrameRequest& f = c.frame;
    if (!a.cam.empty() && !a.view.empty()) throw fit::InputError("give --cam or --view, not both");
    if (!a.view.empty()) {
        const auto view = render::findView(a.view);
        if (!view)
            throw fit::InputError("--view '" + a.view +
                                  "' is unknown (anterior, posterior, left, right, superior, inferior)");
        f.camera = render::cameraForView(*view);
    } else if (!a.cam.empty()) {
        f.camera = render::parseCamera(a.cam);
    }
    std::tie(f.width, f.height) = parseSize(a.size);
    const auto given = [](const std::string& text) {
        return text.empty() ? std::nullopt : std::optional<std::string_view>(text);
    };
    render::applyProjection(f, a.mode, given(a.renderer), given(a.slab));
    f.colormap = render::parseColormap(a.colormap);
    if (!a.window.empty()) f.window = render::parseWindow(a.window, f.colormap);
    c.eps = parseEps(a.eps, "--eps");
    if (a.degree < 0 || a.degree > 3) throw fit::InputError("--degree must be 0..3");
    c.raw = rawLayoutFrom(a.raw);
    if (!a.frames.empty()) {
        if (a.frames != "all") throw fit::InputError("--frames '" + a.frames + "': only 'all' is known");
        if (a.frame || a.turntable || !a.slabSweep.empty() || a.elevation)
            throw fit::InputError(
                "--frames all draws every frame at one camera: not with --frame, --turntable, "
                "--slab-sweep or --elevation");
        c.everyFrame = parseTurntableOutput(a.output);
        checkOutputFolder(c.everyFrame->format == TurntableFormat::Webm ? c.everyFrame->path
                                                                        : framePath(c.everyFrame->path, 0));
        return c;
    }
    if (!a.slabSweep.empty()) {
        if (a.turntable) throw fit::InputError("give --slab-sweep or --turntable, not both");
        if (a.elevation) throw fit::InputError("--elevation is for --turntable N");
        c.slabSweep = checkSlabSweepArgs(a.slabSweep, a.output, f, dicomWebAccessOf(a.dicomWeb));
        return c;
    }
    c.turntable = checkTurntableArgs(a, f);
    return c;
}

bool isVotsFile(const std::string& path) {
    if (fit::isDicomFolder(path)) return false;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fit::InputError("cannot open '" + path + "'");
    char magic[4] = {};
    in.read(magic, 4);
    return in.gcount() == 4 && std::string_view(magic, 4) == fit::VOTS_MAGIC;
}

namespace {

std::optional<float> resolveBackground(const std::string& text, std::array<float, 2> range) {
    if (text == "none") return std::nullopt;
    if (text == "auto") return fit::defaultBackground(range);
    return static_cast<float>(parseNumber(text, "--background"));
}

} // namespace

// Fits `volume` with the options the arguments give for a whole volume whose values span `range` (eps in
// percent of it, its background): the volume itself, or under mpirun one rank's slab of it.
fit::FitResult fitForRender(const fit::Volume& volume, std::array<float, 2> range, const RenderArgs& a,
                            const CheckedArgs& c, std::optional<float> noDataValue) {
    const auto eps = static_cast<float>(c.eps.resolve(range[0], range[1]));
    if (!(eps > 0)) throw fit::InputError("--eps " + a.eps + " is 0 for this volume; give it in data units");
    fit::FitOptions options = render::renderFitOptions(eps, a.degree, resolveBackground(a.background, range),
                                                       fit::parseName<fit::Certify>(a.certify),
                                                       fit::parseName<fit::FitNorm>(a.norm));
    options.noDataValue = noDataValue;
    fit::validateFitOptions(volume, options);
    return fit::fitVotSpace(volume, options);
}

} // namespace vots::cli
