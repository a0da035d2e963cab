// `vots render`: a .vots file or a volume -> MIP / density / reference PNG, headless; argument checks first.
#include "Args.h"
#include "Commands.h"
#include "DistributedRender.h"
#include "MemoryBudgetOption.h"
#include "MpiWorld.h"
#include "RawOptions.h"
#include "SeriesOption.h"
#include "TurntableOutput.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/render/CameraText.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/Turntable.h"
#include "vots/render/VotRenderer.h"
#include "vots/render/WebmWriter.h"
#include "vots/server/FitMeta.h"
#include "vots/server/RenderPolicy.h"

#include <CLI/CLI.hpp>

#include <array>
#include <fstream>
#include <memory>
#include <optional>
#include <tuple>

namespace vots::cli {
namespace {

std::string sizeText(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

std::string certifyName(fit::Certify certify) {
    return certify == fit::Certify::Cells ? "cells" : "samples";
}

struct RenderArgs {
    std::string input;
    std::string output;
    std::string cam;
    std::string view;
    std::string size = sizeText(render::DEFAULT_FRAME_SIDE, render::DEFAULT_FRAME_SIDE);
    std::string mode{render::renderModeName(render::FrameRequest{}.mode)};
    std::string renderer; // empty: what the mode implies (vots; grid for reference)
    std::string slab;     // empty: whole rays
    std::string window;
    std::string colormap{render::colormapName(render::FrameRequest{}.colormap)};
    std::string eps = formatNumber(fit::DEFAULT_EPS_PERCENT) + "%";
    int degree = 3;
    std::string background = "auto";
    std::string certify = certifyName(render::RENDER_FIT_CERTIFY);
    std::string volume;
    std::string memoryBudget;     // empty: the default
    std::string series;           // DICOM SeriesInstanceUID; empty: the folder's only series
    RawArgs raw;                  // the layout of a headerless volume (INPUT, or --volume of a .vots input)
    std::optional<int> turntable; // frames of a turn about the vertical axis; nullopt: one frame
    std::optional<double> elevation; // the turn's elevation; nullopt: the camera's
    bool times = false;              // print the frame's render and composite milliseconds on stderr
};

struct CheckedArgs {
    render::FrameRequest frame;
    fit::EpsSpec eps;
    std::optional<fit::RawLayout> raw;
    std::optional<TurntableOutput> turntable;
};

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
    c.turntable = checkTurntableArgs(a, f);
    return c;
}

bool isVotsFile(const std::string& path) {
    if (fit::isDicomFolder(path)) return false;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw fit::InputError("cannot open '" + path + "'");
    char magic[4] = {};
    in.read(magic, 4);
    return in.gcount() == 4 && std::string(magic, 4) == "VOTS";
}

std::optional<float> resolveBackground(const std::string& text, std::array<float, 2> range) {
    if (text == "none") return std::nullopt;
    if (text == "auto") return fit::defaultBackground(range);
    return static_cast<float>(parseNumber(text, "--background"));
}

// Fits `volume` with the options the arguments give for a whole volume whose values span `range` (eps in
// percent of it, its background): the volume itself, or under mpirun one rank's slab of it.
fit::FitResult fitForRender(const fit::Volume& volume, std::array<float, 2> range, const RenderArgs& a,
                            const CheckedArgs& c) {
    fit::FitOptions options;
    options.eps = static_cast<float>(c.eps.resolve(range[0], range[1]));
    if (!(options.eps > 0))
        throw fit::InputError("--eps " + a.eps + " is 0 for this volume; give it in data units");
    options.degree = a.degree;
    options.background = resolveBackground(a.background, range);
    options.certify = a.certify == "samples" ? fit::Certify::Samples : fit::Certify::Cells;
    fit::validateFitOptions(volume, options);
    return fit::fitVotSpace(volume, options);
}

// Under mpirun: what the ranks composite (one frame of the Vots, any projection), refused before anything
// is read otherwise.
void checkDistributable(const CheckedArgs& c) {
    if (c.turntable || c.frame.renderer == render::RendererKind::Grid)
        throw fit::InputError("under mpirun, vots render draws one frame of the Vots "
                              "(not yet: --renderer grid, --turntable)");
}

// The frame of the whole Vot-Space from every rank's slab, written by rank 0: for mip and density the
// same bytes as one process draws from the same Vots; minip and aip cut each rank's rays to its slab of
// cells (`domain`) and composite the min and the length-weighted mean.
void renderDistributed(const MpiWorld& world, const CheckedArgs& c, render::VotRenderer& vots,
                       const std::optional<render::CellDomain>& domain,
                       std::optional<std::array<float, 2>> volumeRange, const RenderArgs& a) {
    const render::FrameRequest& f = c.frame;
    render::FloatImage frame;
    std::optional<render::FloatImage> lengths;
    auto start = std::chrono::steady_clock::now();
    // A rank that fails to draw (a Vot-Space the walk cannot draw, say) ends every rank.
    world.allOrNone([&] {
        vots.setRayDomain(domain);
        frame = vots.render(f.camera, f.width, f.height, render::RenderOptions{f.mode, f.slab});
        if (f.mode == render::RenderMode::Aip) lengths = vots.rayLengths(f.camera, f.width, f.height, f.slab);
    });
    const double renderMs = a.times ? slowestRankMillisSince(world, start) : 0.0;
    start = std::chrono::steady_clock::now();
    if (lengths)
        compositeMeansOnRoot(world, frame, *lengths);
    else
        compositeOnRoot(world, f.mode, frame);
    if (a.times) reportFrameTimes(world, renderMs, slowestRankMillisSince(world, start));
    std::array<float, 2> range = volumeRange ? *volumeRange : vots.valueRange();
    if (f.mode == render::RenderMode::Density) range = vots.densityRange();
    range = world.unionOfRanges(range);
    if (world.rank() == 0)
        render::writePng(a.output, render::applyDisplay(frame, render::displayFor(f, range)));
}

// Under mpirun: each rank holds the Vots of its z slab, read from the .vots file or fitted from the planes
// it alone reads of the volume, and the frames are composited on rank 0. A failure on any rank ends all.
void runRenderOnRanks(const MpiWorld& world, const RenderArgs& a) {
    CheckedArgs c;
    ZSlab slab;
    fit::VotSpace space;
    std::optional<fit::VolumeSlab> read; // the volume's planes of this slab, when there is a volume
    bool fitHere = false;
    world.allOrNone([&] {
        c = checkArgs(a);
        checkDistributable(c);
        std::string volumePath = a.volume;
        if (isVotsFile(a.input)) {
            if (c.raw && a.volume.empty())
                throw fit::InputError("--raw-* describe a volume; a .vots input has one only with --volume");
            space = fit::readVotSpaceFile(a.input);
            server::restoreMetaFields(space);
            slab = zSlabOfRank(space.dims[2] - 1, world.rank(), world.size());
            space = votsOfSlab(std::move(space), slab, compositesCutRays(c.frame.mode));
        } else {
            if (!a.volume.empty())
                throw fit::InputError("--volume is only for .vots input; INPUT is already a volume");
            volumePath = a.input;
            const auto planesZ = fit::volumeHeaderInfo(a.input, c.raw, a.series).dims[2];
            if (planesZ < 2)
                throw fit::InputError("volume needs at least 2 grid points along every axis to form a cell");
            slab = zSlabOfRank(static_cast<int>(planesZ) - 1, world.rank(), world.size());
            fitHere = true;
        }
        if (volumePath.empty()) return;
        // An empty slab (more ranks than cells) still reads its one plane: its range counts alike.
        checkPlanesFitBudget(volumePath, c.raw, a.memoryBudget, a.series,
                             static_cast<std::uint64_t>(slab.end - slab.first + 1));
        read = loadSlab(volumePath, slab, c.raw, fit::SampleStorage::Float, a.series);
    });
    std::optional<std::array<float, 2>> volumeRange;
    if (read) volumeRange = world.unionOfRanges(read->planes.valueRange());
    fit::FitStats slabStats; // of this rank's fit: its background cells count towards the whole's fill
    if (fitHere) {
        world.allOrNone([&] {
            if (!slab.empty()) {
                fit::FitResult fitted = fitForRender(read->planes, *volumeRange, a, c);
                slabStats = fitted.stats;
                space = std::move(fitted.space);
            }
            placeSlabFitInGrid(space, slab, read->whole);
            read.reset(); // the samples are fitted; only the range is needed from here on
        });
        // Each rank's fit knows only its slab's omitted cells: the fill of the whole volume, as
        // `vots fit` under mpirun gives it, from the sums over the ranks (the slabs split the cells).
        slabStats.backgroundCells =
            world.sumOverRanks(std::vector<std::uint64_t>{slabStats.backgroundCells})[0];
        slabStats.backgroundValueSum = world.sumOverRanks(slabStats.backgroundValueSum);
        space.backgroundFill = fit::backgroundFillOf(slabStats);
    }
    std::unique_ptr<render::EglContext> context;
    std::optional<render::VotRenderer> vots;
    world.allOrNone([&] {
        context = render::EglContext::createOrThrow();
        vots.emplace();
        server::applyRenderPolicy(*vots);
        vots->upload(space);
    });
    std::optional<render::CellDomain> domain;
    if (compositesCutRays(c.frame.mode)) domain = cellDomainOfSlab(slab, space.dims);
    renderDistributed(world, c, *vots, domain, volumeRange, a);
}

void runRender(const RenderArgs& a) {
    const CheckedArgs c = checkArgs(a);
    const bool inputIsVots = isVotsFile(a.input);
    std::optional<fit::Volume> volume;
    std::optional<fit::VotSpace> space;
    if (inputIsVots) {
        space = fit::readVotSpaceFile(a.input);
        server::restoreMetaFields(*space);
        if (!a.volume.empty()) {
            checkVolumeFitsBudget(a.volume, c.raw, a.memoryBudget, a.series);
            volume = fit::loadVolume(a.volume, c.raw, fit::SampleStorage::Float, a.series);
        } else if (c.raw) {
            throw fit::InputError("--raw-* describe a volume; a .vots input has one only with --volume");
        }
        if (c.frame.renderer == render::RendererKind::Grid && !volume)
            throw fit::InputError(
                "--renderer grid (or --mode reference) on a .vots file needs the volume: add "
                "--volume PATH");
    } else {
        if (!a.volume.empty())
            throw fit::InputError("--volume is only for .vots input; INPUT is already a volume");
        // The fit's estimate also for the grid renderer: it covers the samples, their texture and the read.
        checkVolumeFitsBudget(a.input, c.raw, a.memoryBudget, a.series);
        volume = fit::loadVolume(a.input, c.raw, fit::SampleStorage::Float, a.series);
        if (c.frame.renderer != render::RendererKind::Grid)
            space = fitForRender(*volume, volume->valueRange(), a, c).space;
    }

    const auto context = render::EglContext::createOrThrow();
    std::optional<render::GridRenderer> grid;
    std::optional<render::VotRenderer> vots;
    if (c.frame.renderer == render::RendererKind::Grid) {
        grid.emplace().upload(*volume);
    } else {
        vots.emplace();
        server::applyRenderPolicy(*vots);
        vots->upload(*space);
    }
    std::optional<std::array<float, 2>> volumeRange;
    if (volume) volumeRange = volume->valueRange();
    const auto draw = [&](const render::FrameRequest& frame) {
        return render::renderFrame(frame, vots ? &*vots : nullptr, grid ? &*grid : nullptr, volumeRange);
    };
    if (c.turntable) {
        writeTurntable(*c.turntable, c.frame, *a.turntable, a.elevation, draw);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const render::RgbaImage image = draw(c.frame); // with the display pass: one process composites nothing
    if (a.times) reportFrameTimes(MpiWorld::get(), slowestRankMillisSince(MpiWorld::get(), start), 0.0);
    render::writePng(a.output, image);
}

void runRenderCommand(const RenderArgs& a) {
    const MpiWorld& world = MpiWorld::get();
    if (world.distributed())
        runRenderOnRanks(world, a);
    else
        runRender(a);
}

} // namespace

void addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a Vot-Space or volume as MIP (or density) to a PNG");
    cmd->add_option("INPUT", args->input,
                    "A .vots file, or a volume file, DICOM folder or raw file with --raw-* (fitted first at "
                    "--eps for mip/density)")
        ->required();
    cmd->add_option("-o,--output", args->output,
                    "PNG file to write (replaced atomically); with --turntable: frames/%03d.png or turn.webm")
        ->required();
    cmd->add_option("--cam", args->cam,
                    "Camera, e.g. az=30,el=20,zoom=1,pan=0:0,proj=ortho,fov=30 or a view name");
    cmd->add_option("--view", args->view, "anterior|posterior|left|right|superior|inferior");
    cmd->add_option("--size", args->size, "Image size WxH, each 1..8192")->capture_default_str();
    cmd->add_option("--mode", args->mode,
                    "mip, minip, aip (average), density (Vot sizes) or reference (= mip --renderer grid)")
        ->capture_default_str();
    cmd->add_option("--renderer", args->renderer,
                    "vots (analytic, default) or grid (exact over the trilinear samples: the ground truth)");
    cmd->add_option("--slab", args->slab,
                    "OFFSET,THICKNESS in mm: only the slab that far from the volume centre along the view");
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
    cmd->add_option("--volume", args->volume, "The volume of a .vots input (for --renderer grid)");
    cmd->add_option("--turntable", args->turntable,
                    "N views around the vertical axis from the camera's azimuth, 360/N degrees apart, in one "
                    "load and fit: PNG frames (-o with %d) or a VP9 WebM video (-o *.webm, " +
                        std::to_string(render::ANIMATION_FPS) + " frames/s)");
    cmd->add_option("--elevation", args->elevation,
                    "The turntable's elevation in degrees (default: the camera's)");
    cmd->add_flag("--times", args->times,
                  "Print the frame's render and composite milliseconds on stderr (the slowest rank's)");
    addMemoryBudgetOption(*cmd, args->memoryBudget);
    addSeriesOption(*cmd, args->series);
    addRawOptions(*cmd, args->raw);
    cmd->callback([args] { runRenderCommand(*args); });
}

} // namespace vots::cli
