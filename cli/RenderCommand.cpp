// `vots render`: a .vots file or a volume -> MIP / density / reference PNG, headless; argument checks first.
#include "Args.h"
#include "Commands.h"

#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/render/CameraText.h"
#include "vots/render/Colormap.h"
#include "vots/render/DisplaySettings.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/RenderMode.h"
#include "vots/render/VotRenderer.h"

#include <CLI/CLI.hpp>

#include <fstream>
#include <memory>
#include <optional>

namespace vots::cli {
namespace {

struct RenderArgs {
    std::string input;
    std::string output;
    std::string cam;
    std::string view;
    std::string size = "512x512";
    std::string mode = "mip";
    std::string window;
    std::string colormap = "grey";
    std::string eps = "2%";
    int degree = 3;
    std::string background = "auto";
    std::string certify = "cells";
    std::string volume;
};

struct CheckedArgs {
    render::Camera camera;
    int width = 0;
    int height = 0;
    render::RenderMode mode = render::RenderMode::Mip;
    std::optional<render::DisplaySettings> window;
    render::Colormap colormap = render::Colormap::Grey;
    EpsArg eps;
};

std::pair<int, int> parseSize(const std::string& text) {
    const auto x = text.find('x');
    auto bad = [&] { return fit::InputError("--size '" + text + "' is not WxH with 1 <= W, H <= 8192"); };
    if (x == std::string::npos || text.size() > 16) throw bad();
    int v[2];
    const std::string parts[2] = {text.substr(0, x), text.substr(x + 1)};
    for (int i = 0; i < 2; ++i) {
        if (parts[i].empty() || parts[i].size() > 5 ||
            parts[i].find_first_not_of("0123456789") != std::string::npos)
            throw bad();
        v[i] = std::stoi(parts[i]);
    }
    if (v[0] < 1 || v[1] < 1 || v[0] > render::MAX_IMAGE_SIDE || v[1] > render::MAX_IMAGE_SIDE) throw bad();
    return {v[0], v[1]};
}

CheckedArgs checkArgs(const RenderArgs& a) {
    CheckedArgs c;
    if (!a.cam.empty() && !a.view.empty()) throw fit::InputError("give --cam or --view, not both");
    if (!a.view.empty()) {
        const auto view = render::findView(a.view);
        if (!view)
            throw fit::InputError("--view '" + a.view +
                                  "' is unknown (anterior, posterior, left, right, superior, inferior)");
        c.camera = render::cameraForView(*view);
    } else if (!a.cam.empty()) {
        c.camera = render::parseCamera(a.cam);
    }
    const auto [w, h] = parseSize(a.size);
    c.width = w;
    c.height = h;
    c.mode = render::parseRenderMode(a.mode);
    c.colormap = render::parseColormap(a.colormap);
    if (!a.window.empty()) c.window = render::parseWindow(a.window, c.colormap);
    c.eps = parseEps(a.eps, "--eps");
    if (a.degree < 0 || a.degree > 3) throw fit::InputError("--degree must be 0..3");
    return c;
}

bool isVotsFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fit::InputError("cannot open '" + path + "'");
    char magic[4] = {};
    in.read(magic, 4);
    return in.gcount() == 4 && std::string(magic, 4) == "VOTS";
}

std::optional<float> resolveBackground(const std::string& text, const fit::Volume& volume) {
    if (text == "none") return std::nullopt;
    if (text == "auto") return fit::defaultBackground(volume);
    return static_cast<float>(parseNumber(text, "--background"));
}

fit::VotSpace fitForRender(const fit::Volume& volume, const RenderArgs& a, const CheckedArgs& c) {
    const auto range = volume.valueRange();
    fit::FitOptions options;
    options.eps = static_cast<float>(c.eps.resolve(range[0], range[1]));
    if (!(options.eps > 0))
        throw fit::InputError("--eps " + a.eps + " is 0 for this volume; give it in data units");
    options.degree = a.degree;
    options.background = resolveBackground(a.background, volume);
    // Rendering needs the bound between samples too: MIP picks up overshoot (DESIGN §3).
    options.certify = a.certify == "samples" ? fit::Certify::Samples : fit::Certify::Cells;
    fit::validateFitOptions(volume, options);
    return fit::fitVotSpace(volume, options).space;
}

void runRender(const RenderArgs& a) {
    const CheckedArgs c = checkArgs(a);
    const bool inputIsVots = isVotsFile(a.input);
    std::optional<fit::Volume> volume;
    std::optional<fit::VotSpace> space;
    if (inputIsVots) {
        space = fit::readVotSpaceFile(a.input);
        if (!a.volume.empty()) volume = fit::loadVolume(a.volume);
        if (c.mode == render::RenderMode::Reference && !volume)
            throw fit::InputError("--mode reference on a .vots file needs the volume: add --volume PATH");
    } else {
        if (!a.volume.empty())
            throw fit::InputError("--volume is only for .vots input; INPUT is already a volume");
        volume = fit::loadVolume(a.input);
        if (c.mode != render::RenderMode::Reference) space = fitForRender(*volume, a, c);
    }

    const auto context = render::EglContext::createOrThrow();
    render::RgbaImage image;
    if (c.mode == render::RenderMode::Reference) {
        render::GridRenderer grid;
        grid.upload(*volume);
        const auto range = grid.valueRange();
        const auto display = c.window ? *c.window : render::windowForRange(range[0], range[1], c.colormap);
        image = grid.renderRgba(c.camera, c.width, c.height, display);
    } else {
        render::VotRenderer renderer;
        renderer.upload(*space);
        // Default window: the data's full value range (the volume's when we have it).
        auto range = c.mode == render::RenderMode::Density ? renderer.densityRange() : renderer.valueRange();
        if (volume && c.mode == render::RenderMode::Mip) range = volume->valueRange();
        const auto display = c.window ? *c.window : render::windowForRange(range[0], range[1], c.colormap);
        image = renderer.renderRgba(c.camera, c.width, c.height, display, c.mode);
    }
    render::writePng(a.output, image);
}

} // namespace

void addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a Vot-Space or volume as MIP (or density) to a PNG");
    cmd->add_option("INPUT", args->input, "A .vots file, or a volume (fitted first at --eps for mip/density)")
        ->required();
    cmd->add_option("-o,--output", args->output, "PNG file to write (replaced atomically)")->required();
    cmd->add_option("--cam", args->cam,
                    "Camera, e.g. az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30 or a view name");
    cmd->add_option("--view", args->view, "anterior|posterior|left|right|superior|inferior");
    cmd->add_option("--size", args->size, "Image size WxH, each 1..8192")->capture_default_str();
    cmd->add_option("--mode", args->mode, "mip, density or reference (grid ray caster)")
        ->capture_default_str();
    cmd->add_option("--window", args->window, "level,width in data units (default: full value range)");
    cmd->add_option("--colormap", args->colormap, "grey, bone, hot or viridis")->capture_default_str();
    cmd->add_option("--eps", args->eps, "Fit error bound for volume input: data units or percent (2%)")
        ->capture_default_str();
    cmd->add_option("--degree", args->degree, "Fit degree 0..3 for volume input")->capture_default_str();
    cmd->add_option("--background", args->background, "Fit background threshold: auto, none or a value")
        ->capture_default_str();
    cmd->add_option("--certify", args->certify,
                    "Fit certification for volume input: cells (also between samples) or samples")
        ->check(CLI::IsMember({"cells", "samples"}))
        ->capture_default_str();
    cmd->add_option("--volume", args->volume, "The volume of a .vots input (for --mode reference)");
    cmd->callback([args] { runRender(*args); });
}

} // namespace vots::cli
