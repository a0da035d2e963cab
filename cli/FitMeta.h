// The JSON meta block of a Vot-Space file as `vots fit` writes it, and a tolerant reader for it.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Volume.h"

#include <cstdint>
#include <optional>
#include <string>

namespace vots::cli {

/// Everything `vots fit` records about a run.
struct FitRecord {
    std::string sourcePath; // as given on the command line, made absolute
    const fit::Volume* volume = nullptr;
    std::string epsArg;      // as typed ("2%" or "20")
    fit::FitOptions options; // resolved (eps in data units, background value)
    fit::FitStats stats;
    double maxError = 0.0; // max of the stored Vots' err
};

/// Serialises a FitRecord as the file's meta block (one JSON object).
std::string buildFitMeta(const FitRecord& record);

/// The fields `info` and `verify` read back; each is absent when the meta block lacks it or is not
/// JSON (files written by other tools).
struct MetaView {
    bool isJson = false;
    std::optional<int> requestedDegree;
    std::optional<double> fitSeconds;
    std::optional<std::uint64_t> coveredCells; // non-background cells
    std::optional<fit::FocusRegion> focus;
    std::optional<std::string> sourcePath;
    std::optional<std::string> method;
};

MetaView readMeta(const std::string& metaJson);

} // namespace vots::cli
