// `vots verify`: re-checks a .vots file against its volume with the independent verifier; exit 1 on failure.
#include "Args.h"
#include "Commands.h"
#include "DicomWebInput.h"
#include "FrameOption.h"
#include "RawOptions.h"
#include "SeriesOption.h"

#include "vots/fit/Verify.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/FitMeta.h"
#include "vots/meta/VotSpaceRead.h"

#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace vots::cli {
namespace {

struct VerifyArgs {
    std::string file;
    std::string input;
    RawArgs raw;
    std::string series;       // DICOM SeriesInstanceUID; empty: the folder's only series
    std::optional<int> frame; // of a 4D file; empty: frame 0
    DicomWebOptions dicomWeb;
};

/// The bound the file was fitted against: with a focus region, rebuild the field from the meta block
/// so samples inside the focus are held to eps_focus, not to the looser header eps.
std::optional<fit::EpsField> epsFieldOf(const fit::VotSpace& space, const meta::FitMetaView& meta) {
    if (space.epsVaries && meta.focus) return fit::EpsField(space.eps, meta.focus);
    return std::nullopt;
}

void runVerify(const VerifyArgs& a) {
    const auto raw = rawLayoutFrom(a.raw);
    const fit::VotSpace space = meta::readVotSpaceFile(a.file);
    const VolumeInput input(a.input, a.dicomWeb, nullptr, false);
    const fit::Volume volume = input.reading([&] {
        const int frame = frameToRead(input.path(), raw, a.series, a.frame);
        return loadFrame(input.path(), raw, fit::SampleStorage::Float, a.series, frame);
    });
    const meta::FitMetaView meta = meta::readFitMeta(space.metaJson);
    const fit::VerifyReport r = fit::verifyVotSpace(space, volume, epsFieldOf(space, meta));

    std::ostringstream o;
    const auto row = [&o](const char* key) -> std::ostream& {
        return o << std::left << std::setw(22) << key;
    };
    row("Vots") << formatCount(space.vots.size()) << "\n";
    row("max error") << formatNumber(r.maxError) << " (eps " << formatNumber(space.eps)
                     << (space.epsVaries && !meta.focus ? ", varies in space but no focus in meta" : "")
                     << ")\n";
    row("max cell-centre error") << formatNumber(r.maxCellCentreError) << " (vs trilinear interpolation)\n";
    row("samples checked") << formatCount(r.samplesChecked) << "\n";
    row("violations") << formatCount(r.violations) << "\n";
    row("uncovered cells") << formatCount(r.uncoveredCells) << " of " << formatCount(r.nonBackgroundCells)
                           << " non-background\n";
    row("result") << (r.ok ? "OK" : "FAILED") << "\n";
    std::cout << o.str() << std::flush;
    if (!r.ok) {
        std::cerr << "vots: verify failed: "
                  << (r.firstProblem.empty() ? std::string("see the report above") : oneLine(r.firstProblem))
                  << "\n";
        throw CLI::RuntimeError(1); // main returns 1 without printing more
    }
}

} // namespace

void addVerifyCommand(CLI::App& app) {
    auto args = std::make_shared<VerifyArgs>();
    CLI::App* cmd = app.add_subcommand(
        "verify", "Check a .vots file against its volume: coverage and error bound (exit 1 when it fails)");
    cmd->add_option("FILE", args->file, "Vot-Space file")->required();
    cmd->add_option("INPUT", args->input,
                    "The volume (file, DICOM folder or dicomweb+http(s):// series URL) it was fitted to")
        ->required();
    addRawOptions(*cmd, args->raw);
    addSeriesOption(*cmd, args->series);
    addFrameOption(*cmd, args->frame);
    addDicomWebOptions(*cmd, args->dicomWeb);
    cmd->callback([args] { runVerify(*args); });
}

} // namespace vots::cli
