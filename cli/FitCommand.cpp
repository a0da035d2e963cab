// `vots fit`: volume -> Vot-Space file, arguments checked before loading; under mpirun, z cells per rank.
#include "Args.h"
#include "Commands.h"
#include "DicomWebInput.h"
#include "FitNormOption.h"
#include "FrameOption.h"
#include "MemoryBudgetOption.h"
#include "ProgressLine.h"
#include "RawOptions.h"
#include "SeriesOption.h"

#include "vots/dist/mpi/DistributedFit.h"
#include "vots/dist/mpi/MpiWorld.h"
#include "vots/dist/mpi/VotsFileOnRanks.h"

#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/FitMeta.h"
#include "vots/pacs/DicomWebUrl.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

namespace vots::cli {
namespace {

namespace fs = std::filesystem;

struct FitArgs {
    std::string input;
    std::string output;
    std::string eps;
    int degree = 3;
    std::string background = "auto";
    std::string method = "fast";                          // checked by CLI11 against fit::FIT_METHOD_NAMES
    std::string certify = "samples";                      // checked by CLI11 against fit::CERTIFY_NAMES
    std::string norm{fit::nameOf(fit::DEFAULT_FIT_NORM)}; // checked by CLI11 against fit::FIT_NORM_NAMES
    std::string focus;
    std::string epsFocus;
    int threads = 0;
    bool progress = false;
    std::string memoryBudget; // empty: the default
    RawArgs raw;
    std::string series;       // DICOM SeriesInstanceUID; empty: the folder's only series
    std::optional<int> frame; // of a 4D file; empty: frame 0
    DicomWebOptions dicomWeb;
};

/// What can be checked without the volume; the rest is in validateFitOptions.
struct CheckedArgs {
    fit::EpsSpec eps;
    std::optional<fit::FocusRegion> focus;
    std::optional<fit::RawLayout> raw;
};

CheckedArgs checkArgs(const FitArgs& a) {
    CheckedArgs c;
    c.eps = parseEps(a.eps, "--eps");
    if (a.degree < 0 || a.degree > 3)
        throw fit::InputError("--degree " + std::to_string(a.degree) +
                              " is not supported: the Taylor degree must be 0, 1, 2 or 3");
    if (a.threads < 0) throw fit::InputError("--threads must be >= 0 (0: all cores)");
    if (!a.focus.empty()) {
        const auto lastComma = a.focus.find_last_of(',');
        if (std::count(a.focus.begin(), a.focus.end(), ',') != 3)
            throw fit::InputError("--focus: '" + a.focus + "' is not x,y,z,r (grid index units)");
        fit::FocusRegion f;
        f.centerIndex = parseTriple(a.focus.substr(0, lastComma), "--focus");
        f.radius = parseNumber(a.focus.substr(lastComma + 1), "--focus radius");
        if (f.radius <= 0) throw fit::InputError("--focus: the radius must be > 0, got '" + a.focus + "'");
        const fit::EpsSpec e0 = parseEps(a.epsFocus, "--eps-focus", /*allowZero=*/true);
        if (e0.isPercent) throw fit::InputError("--eps-focus takes a value in data units, not a percentage");
        f.epsFocus = static_cast<float>(e0.value);
        c.focus = f;
    }
    c.raw = rawLayoutFrom(a.raw);
    return c;
}

/// Fails before a long fit when the result could not be written anyway.
void checkOutput(const FitArgs& a) {
    const fs::path out(a.output);
    const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw fit::InputError("cannot write '" + a.output + "': no folder '" + dir.string() + "'");
    if (::access(dir.c_str(), W_OK) != 0)
        throw fit::InputError("cannot write '" + a.output + "': folder '" + dir.string() +
                              "' is not writable");
    if (fs::is_directory(out, ec)) throw fit::InputError("cannot write '" + a.output + "': it is a folder");
    if (!pacs::isDicomWebUrl(a.input) && fs::exists(a.input, ec) && fs::equivalent(a.input, out, ec))
        throw fit::InputError("the output '" + a.output + "' is the input file");
}

std::optional<float> resolveBackground(const std::string& text, std::array<float, 2> range) {
    if (text == "none") return std::nullopt;
    if (text == "auto") return fit::defaultBackground(range);
    return static_cast<float>(parseNumber(text, "--background"));
}

/// The fit's options for a volume whose values span `range` (the whole volume's, also on every rank).
fit::FitOptions fitOptionsFor(const FitArgs& a, const CheckedArgs& checked, std::array<float, 2> range) {
    fit::FitOptions options;
    const double eps = checked.eps.resolve(range[0], range[1]);
    if (!(eps > 0))
        throw fit::InputError("--eps " + a.eps + " is 0 for this volume (all values are " +
                              formatNumber(range[0]) + "); give eps in data units");
    options.eps = static_cast<float>(eps);
    options.degree = a.degree;
    options.background = resolveBackground(a.background, range);
    options.method = fit::parseName<fit::FitMethod>(a.method);
    options.certify = fit::parseName<fit::Certify>(a.certify);
    options.norm = fit::parseName<fit::FitNorm>(a.norm);
    options.focus = checked.focus;
    options.threads = a.threads;
    return options;
}

/// The meta block of a fit under mpirun: `meta` (built for the whole volume's grid, which holds no
/// samples) with the whole volume's value range and "ranks": the number of ranks that fitted it.
std::string metaOfRanks(const std::string& meta, std::array<float, 2> range, int ranks) {
    // Ordered: the keys stay where buildFitMeta put them, "ranks" comes last.
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(meta);
    j["source"]["value_range"] = {range[0], range[1]};
    j["ranks"] = ranks;
    return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

/// The meta block of the fit of `volume` (whose grid is enough) whose Vots' largest error is `maxError`.
/// `ranks`: under mpirun, the meta block records them and the whole volume's value range `range`.
std::string fitMetaFor(const FitArgs& a, const std::string& source, const fit::Volume& volume,
                       const fit::FitOptions& options, const fit::FitResult& result, double maxError,
                       std::optional<int> ranks, std::array<float, 2> range) {
    meta::FitProvenance record;
    std::error_code ec;
    const fs::path absolute = fs::absolute(source, ec);
    // A PACS series is named by its URL, which never holds credentials.
    record.sourcePath = pacs::isDicomWebUrl(source) || ec ? source : absolute.lexically_normal().string();
    record.volume = &volume;
    record.epsText = a.eps;
    record.options = options;
    record.options.progress = nullptr;
    record.stats = result.stats;
    record.maxError = maxError;
    record.backgroundFill = result.space.backgroundFill;
    record.frame = a.frame;
    const std::string meta = meta::buildFitMeta(record);
    return ranks ? metaOfRanks(meta, range, *ranks) : meta;
}

/// Says on stdout what was written: `count` Vots of `result`'s fit of `volume`.
void reportFit(const FitArgs& a, const fit::Volume& volume, const fit::FitOptions& options,
               const fit::FitResult& result, std::uint64_t count, double maxError, std::optional<int> ranks) {
    std::cout << "wrote " << a.output << ": " << formatCount(count) << " Vots ("
              << formatNumber(static_cast<double>(count) / static_cast<double>(volume.sampleCount()), 4)
              << " per sample), degree " << result.space.degree << ", max error " << formatNumber(maxError)
              << " (eps " << formatNumber(options.eps) << "), fit in "
              << formatNumber(result.stats.seconds, 3) << " s"
              << (ranks ? " on " + std::to_string(*ranks) + (*ranks == 1 ? " rank" : " ranks") : "") << "\n";
}

void runFit(const FitArgs& a) {
    const CheckedArgs checked = checkArgs(a);
    checkOutput(a);
    const VolumeInput input(
        a.input, a.dicomWeb,
        [&a](const fit::VolumeHeaderInfo& header) {
            checkHeaderFitsBudget(a.input, header, a.memoryBudget, fit::SampleStorage::Source);
        },
        a.progress);
    // Source-typed samples: an int16 CT takes half the memory of floats, and fits to the same Vots.
    const fit::Volume volume = input.reading([&] {
        checkVolumeFitsBudget(input.path(), checked.raw, a.memoryBudget, a.series,
                              fit::SampleStorage::Source);
        const int frame = frameToRead(input.path(), checked.raw, a.series, a.frame);
        fit::Volume loaded =
            loadFrame(input.path(), checked.raw, fit::SampleStorage::Source, a.series, frame);
        if (input.fromPacs()) loaded.name = input.volumeName();
        return loaded;
    });
    const auto range = volume.valueRange();
    fit::FitOptions options = fitOptionsFor(a, checked, range);
    fit::validateFitOptions(volume, options);

    ProgressLine progress(a.progress);
    if (a.progress)
        options.progress = [&progress](double f, const char* stage) { progress.update(f, stage); };
    fit::FitResult result = fit::fitVotSpace(volume, options);
    progress.finish();
    const double maxError = fit::maxStoredError(result.space);
    result.space.metaJson =
        fitMetaFor(a, input.named(), volume, options, result, maxError, std::nullopt, range);
    fit::writeVotSpaceFile(a.output, result.space);
    reportFit(a, volume, options, result, result.space.vots.size(), maxError, std::nullopt);
}

// Under mpirun: each rank reads and fits the planes of its z cells with the whole volume's eps and
// background; each writes its Vots into the one file, rank 0 its frame. A failure on any rank ends every
// rank.
void runFitOnRanks(const dist::MpiWorld& world, const FitArgs& a) {
    CheckedArgs checked;
    dist::RankCells cells;
    fit::PlanesOfGrid read;
    world.allOrNone([&] {
        checked = checkArgs(a);
        if (a.frame == FRAME_MAX) throw fit::InputError("--frame max runs in one process, not under mpirun");
        if (world.rank() == 0) checkOutput(a);
        cells = dist::fitCellsOfRank(world, fit::volumeHeaderInfo(a.input, checked.raw, a.series).dims[2]);
        const auto planes = static_cast<std::uint64_t>(cells.end - cells.first + 1);
        checkPlanesFitBudget(a.input, checked.raw, a.memoryBudget, a.series, planes,
                             fit::SampleStorage::Source);
        read = dist::loadPlanesOfCells(a.input, cells, checked.raw, fit::SampleStorage::Source, a.series,
                                       a.frame.value_or(0));
    });
    // The whole volume's range: the union of the ranks' planes', which cover every plane.
    const std::array<float, 2> range = world.unionOfRanges(read.planes.valueRange());
    fit::FitOptions options;
    fit::FitResult result;
    world.allOrNone([&] {
        options = fitOptionsFor(a, checked, range);
        // The focus is named in the whole volume's index space; each rank's field is moved into its planes.
        options.partOfGrid = fit::PartOfGrid{cells.first, read.whole.dims};
        options.noDataValue = range[0]; // the whole volume's lowest finite sample, not this rank's
        fit::validateFitOptions(read.planes, options);
        ProgressLine progress(a.progress && world.rank() == 0); // rank 0's fit stands for the others
        if (a.progress && world.rank() == 0)
            options.progress = [&progress](double f, const char* stage) { progress.update(f, stage); };
        result = fit::fitVotSpace(read.planes, options);
        progress.finish();
        options.progress = nullptr;
    });
    read.planes = fit::Volume{}; // the samples are fitted: free them before the file is written
    const std::uint64_t count = dist::reduceFitOverRanks(world, result, cells, read.whole);
    const double maxError = world.maxOverRanks(fit::maxStoredError(result.space));
    world.allOrNone([&] {
        if (world.rank() == 0)
            result.space.metaJson =
                fitMetaFor(a, a.input, read.whole, options, result, maxError, world.size(), range);
    });
    dist::writeVotSpaceOnRanks(world, a.output, result.space);
    if (world.rank() == 0) reportFit(a, read.whole, options, result, count, maxError, world.size());
}

void runFitCommand(const FitArgs& a) {
    const dist::MpiWorld& world = dist::MpiWorld::get();
    if (world.launched() && pacs::isDicomWebUrl(a.input))
        world.allOrNone([] { // one message, from rank 0
            throw fit::InputError(
                "a dicomweb+http(s):// input is read by one process: fit it without mpirun, or "
                "retrieve it into a folder first");
        });
    if (world.launched())
        runFitOnRanks(world, a);
    else
        runFit(a);
}

} // namespace

void addFitCommand(CLI::App& app) {
    auto args = std::make_shared<FitArgs>();
    CLI::App* cmd = app.add_subcommand("fit", "Fit a Vot-Space to a volume and write it to a .vots file");
    cmd->add_option("INPUT", args->input,
                    "Volume file: .nrrd/.nhdr, .nii/.nii.gz, .mgh/.mgz, .mhd/.mha, a folder of DICOM files, "
                    "a series on a PACS "
                    "(dicomweb+http(s)://HOST:PORT/ROOT/studies/STUDY/series/SERIES), or raw with --raw-*")
        ->required();
    cmd->add_option("-o,--output", args->output, "Vot-Space file to write (replaced atomically)")->required();
    cmd->add_option("--eps", args->eps,
                    "Error bound in data units (e.g. 20) or percent of the value range (2%)")
        ->required();
    cmd->add_option("--degree", args->degree, "Taylor degree 0..3")->capture_default_str();
    cmd->add_option("--background", args->background,
                    "Cells with all corners below this value are omitted; 'auto' (min + 1 % of the range) or "
                    "'none'")
        ->capture_default_str();
    cmd->add_option("--method", args->method, "paper (seed, grow, greedy cover) or fast (split and merge)")
        ->check(CLI::IsMember(fit::acceptedNames<fit::FitMethod>()))
        ->capture_default_str();
    cmd->add_option("--certify", args->certify,
                    "samples: bound at grid samples; cells: also at cell centres and edge midpoints")
        ->check(CLI::IsMember(fit::acceptedNames<fit::Certify>()))
        ->capture_default_str();
    addFitNormOption(*cmd, args->norm);
    CLI::Option* focus = cmd->add_option("--focus", args->focus, "Focus sphere x,y,z,r in grid index units");
    CLI::Option* epsFocus =
        cmd->add_option("--eps-focus", args->epsFocus, "Error bound inside the focus sphere");
    epsFocus->needs(focus);
    focus->needs(epsFocus);
    cmd->add_option("--threads", args->threads, "Worker threads (0: all cores)")->capture_default_str();
    cmd->add_flag("--progress", args->progress, "Show progress on stderr");
    addMemoryBudgetOption(*cmd, args->memoryBudget);
    addRawOptions(*cmd, args->raw);
    addSeriesOption(*cmd, args->series);
    addFrameOption(*cmd, args->frame);
    addDicomWebOptions(*cmd, args->dicomWeb);
    cmd->callback([args] { runFitCommand(*args); });
}

} // namespace vots::cli
