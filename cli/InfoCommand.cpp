// `vots info`: summary of a .vots file (grid, degree, eps, Vot count, box sizes), as text or JSON.
#include "Args.h"
#include "Commands.h"
#include "FrameOption.h"

#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/FitMeta.h"
#include "vots/meta/VotSpaceRead.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace vots::cli {
namespace {

using json = nlohmann::ordered_json;

struct InfoArgs {
    std::string file;
    bool json = false;
};

/// Box size classes by largest side in cells.
constexpr std::array<const char*, 7> SIZE_LABELS{"1", "2", "3-4", "5-8", "9-16", "17-32", "33+"};

std::size_t sizeClass(const fit::Box& box) {
    const int side = std::max({box.cells(0), box.cells(1), box.cells(2)});
    std::size_t k = 0;
    for (int upper = 1; k + 1 < SIZE_LABELS.size() && side > upper; upper *= 2)
        ++k;
    return k;
}

struct Summary {
    std::array<std::size_t, SIZE_LABELS.size()> histogram{};
    double maxError = 0.0;
    double perSample = 0.0;
    std::optional<double> perNonBackgroundCell;
};

Summary summarise(const fit::VotSpace& s, const meta::FitMetaView& meta) {
    Summary sum;
    for (const fit::Vot& v : s.vots) {
        ++sum.histogram[sizeClass(v.box)];
        sum.maxError = std::max(sum.maxError, double{v.err});
    }
    const double samples = double(s.dims[0]) * double(s.dims[1]) * double(s.dims[2]);
    const auto count = static_cast<double>(s.vots.size());
    sum.perSample = count / samples;
    if (meta.coveredCells && *meta.coveredCells > 0)
        sum.perNonBackgroundCell = count / double(*meta.coveredCells);
    return sum;
}

/// The norm a fit by `vots fit` or the server accepted boxes by: its block names only a minimax one (a
/// least-squares fit's block kept its bytes from before the norm could be chosen); nullopt for a block
/// that is no such fit's (no fit.method), as from other tools.
std::optional<std::string> fitNormOf(const meta::FitMetaView& meta) {
    if (!meta.method) return std::nullopt;
    return meta.norm.value_or("lsq");
}

template <class T> json orNull(const std::optional<T>& v) {
    return v ? json(*v) : json(nullptr);
}

json toJson(const std::string& path, const fit::VotSpace& s, const meta::FitMetaView& meta,
            const Summary& sum) {
    json hist = json::array();
    for (std::size_t k = 0; k < SIZE_LABELS.size(); ++k)
        hist.push_back({{"largest_side_cells", SIZE_LABELS[k]}, {"count", sum.histogram[k]}});
    return {
        {"file", path},
        {"version", fit::VOTS_FILE_VERSION},
        {"dims", s.dims},
        {"spacing", s.spacing},
        {"origin", s.origin},
        {"degree", s.degree},
        {"requested_degree", orNull(meta.requestedDegree)},
        {"eps", s.eps},
        {"eps_varies", s.epsVaries},
        {"background", std::isfinite(s.background) ? json(s.background) : json(nullptr)},
        {"background_fill", orNull(meta.backgroundFill)},
        {"frame", orNull(meta.frame)},
        {"non_finite_samples", meta.nonFiniteSamples},
        {"vot_count", s.vots.size()},
        {"vots_per_sample", sum.perSample},
        {"vots_per_nonbackground_cell", orNull(sum.perNonBackgroundCell)},
        {"box_size_histogram", hist},
        {"max_error", sum.maxError},
        {"fit_seconds", orNull(meta.fitSeconds)},
        {"fit_norm", orNull(fitNormOf(meta))},
        {"certify", orNull(meta.certify)},
        {"meta", meta.isJson ? json::parse(s.metaJson) : json(nullptr)},
    };
}

// "ranks" of a file `vots fit` wrote under mpirun (FitCommand.cpp's metaOfRanks); nullopt for any other file.
std::optional<long long> ranksOf(const std::string& metaJson) {
    const json j = json::parse(metaJson, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("ranks") || !j["ranks"].is_number_integer()) return std::nullopt;
    return j["ranks"].get<long long>();
}

void printText(const std::string& path, const fit::VotSpace& s, const meta::FitMetaView& meta,
               const Summary& sum) {
    std::ostringstream o;
    const auto row = [&o](const char* key) -> std::ostream& {
        return o << std::left << std::setw(12) << key;
    };
    row("file") << path << " (Vot-Space v" << fit::VOTS_FILE_VERSION << ")\n";
    row("grid") << s.dims[0] << " x " << s.dims[1] << " x " << s.dims[2] << " points, spacing "
                << formatNumber(s.spacing[0]) << " x " << formatNumber(s.spacing[1]) << " x "
                << formatNumber(s.spacing[2]) << ", origin (" << formatNumber(s.origin[0]) << ", "
                << formatNumber(s.origin[1]) << ", " << formatNumber(s.origin[2]) << ")\n";
    row("degree") << s.degree << " (header)";
    if (meta.requestedDegree) o << ", " << *meta.requestedDegree << " requested";
    o << "\n";
    if (meta.frame == FRAME_MAX)
        row("frame") << "max (the maximum over the frames of a 4D file)\n";
    else if (meta.frame)
        row("frame") << *meta.frame << " (of a 4D file)\n";
    if (meta.nonFiniteSamples > 0)
        row("no data") << formatCount(meta.nonFiniteSamples)
                       << " samples NaN or Inf (left out as omitted cells are)\n";
    row("eps") << formatNumber(s.eps) << (s.epsVaries ? " (context; varies in space)" : "");
    if (meta.epsText) o << " (given as " << *meta.epsText << ")";
    o << "\n";
    if (const auto norm = fitNormOf(meta)) {
        row("fit") << *meta.method << " method, " << (*norm == "lsq" ? "least-squares" : *norm) << " norm";
        if (meta.certify)
            o << ", certified at " << (*meta.certify == "cells" ? "samples and cells" : *meta.certify);
        o << "\n";
    }
    row("background") << (std::isfinite(s.background) ? formatNumber(s.background) : std::string("none"));
    if (meta.backgroundFill)
        o << " (omitted cells count as " << formatNumber(*meta.backgroundFill) << " in minip and aip)";
    o << "\n";
    row("Vots") << formatCount(s.vots.size()) << " (" << formatNumber(sum.perSample, 4) << " per sample";
    if (sum.perNonBackgroundCell)
        o << ", " << formatNumber(*sum.perNonBackgroundCell, 4) << " per non-background cell";
    o << ")\n";
    row("max error") << formatNumber(sum.maxError) << "\n";
    if (meta.fitSeconds) row("fit time") << formatNumber(*meta.fitSeconds, 3) << " s\n";
    if (const auto ranks = ranksOf(s.metaJson)) row("ranks") << *ranks << " (fitted under mpirun)\n";
    o << "box sizes (largest side in cells):\n";
    for (std::size_t k = 0; k < SIZE_LABELS.size(); ++k) {
        const double share = s.vots.empty() ? 0.0 : 100.0 * double(sum.histogram[k]) / double(s.vots.size());
        o << "  " << std::left << std::setw(6) << SIZE_LABELS[k] << std::right << std::setw(12)
          << formatCount(sum.histogram[k]) << "  " << std::fixed << std::setprecision(1) << std::setw(5)
          << share << " %\n";
        o.unsetf(std::ios::floatfield);
    }
    std::cout << o.str();
}

void runInfo(const InfoArgs& a) {
    const fit::VotSpace space = meta::readVotSpaceFile(a.file);
    const meta::FitMetaView meta = meta::readFitMeta(space.metaJson);
    const Summary sum = summarise(space, meta);
    if (a.json)
        std::cout << toJson(a.file, space, meta, sum).dump(-1, ' ', false, json::error_handler_t::replace)
                  << "\n";
    else
        printText(a.file, space, meta, sum);
}

} // namespace

void addInfoCommand(CLI::App& app) {
    auto args = std::make_shared<InfoArgs>();
    CLI::App* cmd =
        app.add_subcommand("info", "Describe a .vots file: grid, degree, eps, Vot count, box sizes");
    cmd->add_option("FILE", args->file, "Vot-Space file")->required();
    cmd->add_flag("--json", args->json, "Print one JSON object instead of text");
    cmd->callback([args] { runInfo(*args); });
}

} // namespace vots::cli
