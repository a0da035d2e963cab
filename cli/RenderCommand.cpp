// `vots render`: a .vots file or a volume -> MIP / density / reference PNG or turntable, headless, in one
// process or (RenderOnRanks.cpp) across the ranks of mpirun.
#include "Args.h"
#include "Commands.h"
#include "DicomWebInput.h"
#include "FitNormOption.h"
#include "FrameOption.h"
#include "MemoryBudgetOption.h"
#include "RawOptions.h"
#include "RenderArgs.h"
#include "RenderOnRanks.h"
#include "SeriesOption.h"
#include "SlabSweepOutput.h"
#include "TurntableOutput.h"

#include "vots/dist/mpi/CollectiveComposite.h"
#include "vots/dist/mpi/MpiWorld.h"
#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/pacs/DicomWebUrl.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/FrameRequest.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/Turntable.h"
#include "vots/render/VotRenderer.h"
#include "vots/render/WebmWriter.h"
#include "vots/server/RenderPolicy.h"

#include <CLI/CLI.hpp>

#include <array>
#include <memory>
#include <optional>
#include <utility>

namespace vots::cli {
namespace {

/// A volume as the render reads it, and its DICOM identity when a sweep writes a derived series of it.
struct RenderVolume {
    fit::Volume volume;
    std::optional<fit::DicomIdentity> identity; // the source's patient and study; nullopt: not DICOM
};

/// Loads a volume file, folder or PACS series (its spool folder is gone once the samples are in memory),
/// refused before its samples are read when the budget cannot hold it. A DICOM series' identity is read
/// when `withIdentity`, while a PACS series' spool is still there.
RenderVolume loadRenderVolume(const std::string& named, const RenderArgs& a, const CheckedArgs& c,
                              bool withIdentity) {
    const VolumeInput input(
        named, a.dicomWeb,
        [&](const fit::VolumeHeaderInfo& header) { checkHeaderFitsBudget(named, header, a.memoryBudget); },
        false);
    return input.reading([&] {
        checkVolumeFitsBudget(input.path(), c.raw, a.memoryBudget, a.series);
        const int frame = frameToRead(input.path(), c.raw, a.series, a.frame);
        RenderVolume loaded{loadFrame(input.path(), c.raw, fit::SampleStorage::Float, a.series, frame), {}};
        if (withIdentity && fit::isDicomFolder(input.path()))
            loaded.identity = fit::readDicomIdentity(input.path(), a.series);
        return loaded;
    });
}

/// `--frames all`: each frame of a 4D file loaded, fitted (or uploaded for the grid renderer) and drawn at
/// one camera in turn, with the first frame's value range for all (one window over time), written as a
/// turntable's frames are (PNG frames or a WebM, all or nothing).
void renderEveryFrame(const RenderArgs& a, const CheckedArgs& c) {
    if (pacs::isDicomWebUrl(a.input) || isVotsFile(a.input))
        throw fit::InputError("--frames all needs a 4D volume file as INPUT");
    checkVolumeFitsBudget(a.input, c.raw, a.memoryBudget, a.series);
    const std::uint64_t frames = fit::volumeHeaderInfo(a.input, c.raw, a.series).frames;
    const auto context = render::EglContext::createOrThrow();
    TurntableWriter writer(*c.everyFrame, c.frame.width, c.frame.height);
    std::optional<std::array<float, 2>> range;
    for (std::uint64_t k = 0; k < frames; ++k) {
        const fit::Volume volume =
            fit::loadVolume(a.input, c.raw, fit::SampleStorage::Float, a.series, static_cast<int>(k));
        if (!range) range = volume.valueRange();
        std::optional<render::GridRenderer> grid;
        std::optional<render::VotRenderer> vots;
        if (c.frame.renderer == render::RendererKind::Grid) {
            grid.emplace().upload(volume);
        } else {
            vots.emplace();
            server::applyRenderPolicy(*vots);
            vots->upload(fitForRender(volume, *range, a, c).space);
        }
        writer.add(render::renderFrame(c.frame, vots ? &*vots : nullptr, grid ? &*grid : nullptr, range));
    }
    writer.finish();
}

void runRender(const RenderArgs& a) {
    const CheckedArgs c = checkArgs(a);
    if (c.everyFrame) {
        renderEveryFrame(a, c);
        return;
    }
    const bool inputIsVots = !pacs::isDicomWebUrl(a.input) && isVotsFile(a.input);
    // A derived DICOM series joins the source's patient and study (INPUT or a .vots input's --volume).
    const bool withIdentity = c.slabSweep && c.slabSweep->format != SweepFormat::Png;
    std::optional<fit::DicomIdentity> source;
    std::optional<fit::Volume> volume;
    std::optional<fit::VotSpace> space;
    std::optional<render::SlabSweepPlan> sweep; // planned from the grid before the fit and the GL context
    if (inputIsVots) {
        space = meta::readVotSpaceFile(a.input);
        if (c.slabSweep) sweep = planSweep(*c.slabSweep, c.frame, render::sceneBounds(*space));
        if (!a.volume.empty()) {
            RenderVolume loaded = loadRenderVolume(a.volume, a, c, withIdentity);
            volume = std::move(loaded.volume);
            source = std::move(loaded.identity);
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
        RenderVolume loaded = loadRenderVolume(a.input, a, c, withIdentity);
        volume = std::move(loaded.volume);
        source = std::move(loaded.identity);
        if (c.slabSweep) sweep = planSweep(*c.slabSweep, c.frame, render::sceneBounds(*volume));
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
    if (c.slabSweep) {
        render::Renderer& renderer = grid ? static_cast<render::Renderer&>(*grid) : *vots;
        writeSlabSweep(*c.slabSweep, *sweep, c.frame, renderer, volumeRange.value_or(renderer.valueRange()),
                       source, draw);
        return;
    }
    if (c.turntable) {
        writeTurntable(*c.turntable, c.frame, *a.turntable, a.elevation, draw);
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    const render::RgbaImage image = draw(c.frame); // with the display pass: one process composites nothing
    if (a.times)
        dist::reportFrameTimes(dist::MpiWorld::get(),
                               dist::slowestRankMillisSince(dist::MpiWorld::get(), start), 0.0);
    render::writePng(a.output, image);
}

void runRenderCommand(const RenderArgs& a) {
    const dist::MpiWorld& world = dist::MpiWorld::get();
    if (world.distributed() && !a.slabSweep.empty())
        throw fit::InputError("--slab-sweep runs in one process, not under mpirun");
    if (world.distributed() && !a.frames.empty())
        throw fit::InputError("--frames all runs in one process, not under mpirun");
    if (world.distributed() && (pacs::isDicomWebUrl(a.input) || pacs::isDicomWebUrl(a.volume)))
        world.allOrNone([] { // one message, from rank 0
            throw fit::InputError(
                "a dicomweb+http(s):// input is read by one process: render it without mpirun, "
                "or retrieve it into a folder first");
        });
    if (world.distributed())
        runRenderOnRanks(world, a);
    else
        runRender(a);
}

} // namespace

void addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand("render", "Render a Vot-Space or volume as MIP (or density) to a PNG");
    cmd->add_option(
           "INPUT", args->input,
           "A .vots file, or a volume file, DICOM folder, PACS series (dicomweb+http(s)://...) or raw file "
           "with --raw-* (fitted first at --eps for mip/density)")
        ->required();
    cmd->add_option(
           "-o,--output", args->output,
           "PNG file to write (replaced atomically); with --turntable: frames/%03d.png or turn.webm; "
           "with --slab-sweep: slabs/%03d.dcm (DICOM series), slabs/%03d.png, or "
           "dicomweb+http(s)://HOST:PORT/ROOT "
           "(the DICOM series stored on a PACS with STOW-RS)")
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
        ->check(CLI::IsMember(fit::acceptedNames<fit::Certify>()))
        ->capture_default_str();
    addFitNormOption(*cmd, args->norm);
    cmd->add_option("--volume", args->volume, "The volume of a .vots input (for --renderer grid)");
    cmd->add_option("--turntable", args->turntable,
                    "N views around the vertical axis from the camera's azimuth, 360/N degrees apart, in one "
                    "load and fit: PNG frames (-o with %d) or a VP9 WebM video (-o *.webm, " +
                        std::to_string(render::ANIMATION_FPS) + " frames/s)");
    cmd->add_option(
        "--slab-sweep", args->slabSweep,
        "THICKNESS,STEP in mm: slabs THICKNESS thick every STEP along the view through the whole "
        "volume, one image each: 1 + ceil((L - THICKNESS) / STEP) slabs centred on the volume, L its "
        "depth along the view (orthographic; --size and the other options apply to each). -o "
        "DIR/%03d.dcm writes a derived DICOM series in the source's units, DIR/%03d.png the "
        "display images. Pixel spacing: the view's extent, 2R/(zoom*H) mm with R the half-"
        "diagonal of the volume's box and H the image height");
    cmd->add_option("--elevation", args->elevation,
                    "The turntable's elevation in degrees (default: the camera's)");
    cmd->add_flag("--times", args->times,
                  "Print the frame's render and composite milliseconds on stderr (the slowest rank's)");
    addMemoryBudgetOption(*cmd, args->memoryBudget);
    addSeriesOption(*cmd, args->series);
    addFrameOption(*cmd, args->frame);
    cmd->add_option(
        "--frames", args->frames,
        "'all': every frame of a 4D file fitted and drawn at one camera (the first frame's window), "
        "-o DIR/%03d.png (one PNG per frame) or cine.webm");
    addRawOptions(*cmd, args->raw);
    addDicomWebOptions(*cmd, args->dicomWeb);
    cmd->callback([args] { runRenderCommand(*args); });
}

} // namespace vots::cli
