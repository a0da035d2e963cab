// `vots render` under mpirun: every rank reads and draws its z cells; rank 0 writes the composited frames.
#include "RenderOnRanks.h"

#include "FrameOption.h"
#include "MemoryBudgetOption.h"
#include "TurntableOutput.h"

#include "vots/dist/CompositeOp.h"
#include "vots/dist/RankCells.h"
#include "vots/dist/WholeFill.h"
#include "vots/dist/mpi/CollectiveComposite.h"
#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/DisplayPass.h"
#include "vots/render/EglContext.h"
#include "vots/render/GridRenderer.h"
#include "vots/render/Png.h"
#include "vots/render/VotRenderer.h"
#include "vots/server/RenderPolicy.h"

#include <memory>
#include <optional>

namespace vots::cli {
namespace {

using dist::MpiWorld;
using dist::RankCells;

// What this rank draws from: the Vots of its cells (read from the .vots file, or fitted from its planes),
// or with the grid renderer its planes themselves.
struct RankInput {
    CheckedArgs c;
    RankCells cells;
    fit::VotSpace space;
    std::optional<fit::PlanesOfGrid> read; // the volume's planes of these cells, when there is a volume
    bool fitHere = false;
    bool grid = false;
};

// The z cells of a volume file this rank takes.
RankCells cellsOfVolume(const MpiWorld& world, const std::string& path, const RenderArgs& a,
                        const CheckedArgs& c) {
    return dist::cellsOfRankInVolume(path, world.rank(), world.size(), c.raw, a.series);
}

// The arguments' checks and this rank's reads; a step of allOrNone (no collective inside).
void readRankInput(const MpiWorld& world, const RenderArgs& a, RankInput& in) {
    in.c = checkArgs(a);
    in.grid = in.c.frame.renderer == render::RendererKind::Grid;
    std::string volumePath = a.volume;
    if (isVotsFile(a.input)) {
        if (in.c.raw && a.volume.empty())
            throw fit::InputError("--raw-* describe a volume; a .vots input has one only with --volume");
        if (in.grid) {
            // The grid draws the samples: the Vots are not needed, and no rank reads them all.
            if (a.volume.empty())
                throw fit::InputError(
                    "--renderer grid (or --mode reference) on a .vots file needs the volume: add "
                    "--volume PATH");
            in.cells = cellsOfVolume(world, a.volume, a, in.c);
        } else {
            in.space = meta::readVotSpaceFile(a.input);
            in.cells = dist::cellsOfRank(in.space.dims[2] - 1, world.rank(), world.size());
            in.space =
                dist::votsOfCells(std::move(in.space), in.cells, dist::compositesCutRays(in.c.frame.mode));
        }
    } else {
        if (!a.volume.empty())
            throw fit::InputError("--volume is only for .vots input; INPUT is already a volume");
        volumePath = a.input;
        in.cells = cellsOfVolume(world, a.input, a, in.c);
        in.fitHere = !in.grid;
    }
    if (volumePath.empty()) return;
    if (a.frame == FRAME_MAX) throw fit::InputError("--frame max runs in one process, not under mpirun");
    // An empty range of cells (more ranks than cells) still reads its one plane: its range counts alike.
    checkPlanesFitBudget(volumePath, in.c.raw, a.memoryBudget, a.series,
                         static_cast<std::uint64_t>(in.cells.end - in.cells.first + 1));
    in.read = dist::loadPlanesOfCells(volumePath, in.cells, in.c.raw, fit::SampleStorage::Float, a.series,
                                      a.frame.value_or(0));
}

// Fits this rank's planes with the options of the whole volume and places the Vots in its grid, with the
// whole volume's fill (dist::wholeVolumeFill, as every distributed fit and frame takes it).
void fitRankCells(const MpiWorld& world, const RenderArgs& a, RankInput& in, std::array<float, 2> range) {
    fit::FitStats cellsStats; // of this rank's fit: its background cells count towards the whole's fill
    world.allOrNone([&] {
        if (!in.cells.empty()) {
            // No data counts as the whole volume's lowest finite sample, not this rank's.
            fit::FitResult fitted = fitForRender(in.read->planes, range, a, in.c, range[0]);
            cellsStats = fitted.stats;
            in.space = std::move(fitted.space);
        }
        dist::placeCellsFitInGrid(in.space, in.cells, in.read->whole);
        in.read.reset(); // the samples are fitted; only the range is needed from here on
    });
    in.space.backgroundFill =
        dist::wholeVolumeFill(world.gatherOnEveryRank(dist::backgroundSumsOf(cellsStats)));
}

// This rank's renderer: its Vots (rays cut to its cells where the composite needs it), or its planes.
struct RankDrawer {
    std::optional<render::VotRenderer> vots;
    std::optional<render::GridRenderer> grid;
    std::optional<render::CellDomain> domain;
};

// One frame of every rank composited on rank 0 (elsewhere: the rank's own frame). A collective.
render::FloatImage compositedFrame(const MpiWorld& world, const render::FrameRequest& f, RankDrawer& d,
                                   bool times) {
    render::FloatImage frame;
    std::optional<render::FloatImage> lengths;
    auto start = std::chrono::steady_clock::now();
    // A rank that fails to draw (a Vot-Space the walk cannot draw, say) ends every rank.
    world.allOrNone([&] {
        const render::RenderOptions options{f.mode, f.slab};
        if (d.grid) {
            frame = d.grid->render(f.camera, f.width, f.height, options);
            return;
        }
        d.vots->setRayDomain(d.domain);
        frame = d.vots->render(f.camera, f.width, f.height, options);
        if (f.mode == render::RenderMode::Aip)
            lengths = d.vots->rayLengths(f.camera, f.width, f.height, f.slab);
    });
    const double renderMs = times ? dist::slowestRankMillisSince(world, start) : 0.0;
    start = std::chrono::steady_clock::now();
    const auto source = d.grid ? dist::RankSource::Grid : dist::RankSource::Vots;
    dist::compositeOnRoot(world, dist::compositeOpFor(f.mode, source), frame, lengths);
    if (times) dist::reportFrameTimes(world, renderMs, dist::slowestRankMillisSince(world, start));
    return frame;
}

} // namespace

void runRenderOnRanks(const MpiWorld& world, const RenderArgs& a) {
    RankInput in;
    world.allOrNone([&] { readRankInput(world, a, in); });
    const CheckedArgs& c = in.c;
    std::optional<std::array<float, 2>> volumeRange;
    if (in.read) volumeRange = world.unionOfRanges(in.read->planes.valueRange());
    if (in.fitHere) fitRankCells(world, a, in, *volumeRange);

    std::unique_ptr<render::EglContext> context;
    RankDrawer drawer;
    std::optional<TurntableWriter> writer; // rank 0's, for --turntable
    world.allOrNone([&] {
        context = render::EglContext::createOrThrow();
        if (in.grid) {
            drawer.grid.emplace().uploadPlanes(in.read->planes, in.cells.first, in.read->whole);
            drawer.grid->useNoDataValue((*volumeRange)[0]); // the whole volume's, as the one process draws
            in.read.reset();                                // the samples are in the textures
        } else {
            drawer.vots.emplace();
            server::applyRenderPolicy(*drawer.vots);
            drawer.vots->upload(in.space);
        }
        if (c.turntable && world.rank() == 0) writer.emplace(*c.turntable, c.frame.width, c.frame.height);
    });
    if (!in.grid && dist::compositesCutRays(c.frame.mode))
        drawer.domain = dist::cutRayDomainOf(in.cells, in.space.dims);

    // The display window of the whole: the volume's range (or the Vots', or their sizes for the density).
    std::array<float, 2> range{0.f, 0.f};
    if (volumeRange) range = *volumeRange;
    if (drawer.vots) {
        if (!volumeRange) range = drawer.vots->valueRange();
        if (c.frame.mode == render::RenderMode::Density) range = drawer.vots->densityRange();
    }
    range = world.unionOfRanges(range);
    const auto displayed = [&](const render::FrameRequest& f, const render::FloatImage& frame) {
        return render::applyDisplay(frame, render::displayFor(f, range));
    };

    if (!c.turntable) {
        const render::FloatImage frame = compositedFrame(world, c.frame, drawer, a.times);
        world.allOrNone([&] {
            if (world.rank() == 0) render::writePng(a.output, displayed(c.frame, frame));
        });
        return;
    }
    // Rank 0 writes each frame while the ranks draw the next; a failed write ends every rank at the next
    // frame, and the writer then leaves no frame behind.
    for (int k = 0; k < *a.turntable; ++k) {
        const render::FrameRequest f = turntableFrame(c.frame, *a.turntable, k, a.elevation);
        const render::FloatImage frame = compositedFrame(world, f, drawer, false);
        world.allOrNone([&] {
            if (writer) writer->add(displayed(f, frame));
        });
    }
    world.allOrNone([&] {
        if (writer) writer->finish();
    });
}

} // namespace vots::cli
