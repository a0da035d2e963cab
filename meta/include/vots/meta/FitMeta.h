// The meta block of a .vots file: one JSON schema for `vots fit` and the server's cache, and its reader.
#pragma once

#include "vots/fit/EpsField.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/PatientAxes.h"
#include "vots/fit/Volume.h"

#include <cstdint>
#include <optional>
#include <string>

namespace vots::meta {

/// Everything recorded about one fit.
struct FitProvenance {
    std::string sourcePath; // the volume file, absolute
    const fit::Volume* volume = nullptr;
    std::string epsText;     // as the person typed it ("2%" or "20"); empty: none typed (null in the block)
    fit::FitOptions options; // resolved (eps in data units, background value); progress and cancel unused
    fit::FitStats stats;
    double maxError = 0.0; // max of the stored Vots' err
    std::string cacheKey;  // the server's key for the fit (its cache files carry it); empty: no key
    std::optional<float> backgroundFill; // VotSpace::backgroundFill; absent: no key in the block
    std::optional<int> frame;            // the frame of a 4D file that was fitted; absent: no key
};

/// The meta block (one JSON object). Files without a cache key have exactly the keys `vots fit` wrote
/// before the server shared this schema.
std::string buildFitMeta(const FitProvenance& fit);

/// The fields read back; each is absent when the block lacks it or is not JSON (files of other tools).
struct FitMetaView {
    bool isJson = false;
    std::optional<int> requestedDegree;
    std::optional<double> fitSeconds;          // also read from the server's earlier cache blocks
    std::optional<std::uint64_t> coveredCells; // non-background cells
    std::optional<fit::FocusRegion> focus;
    std::optional<std::string> sourcePath;
    std::optional<std::string> method;
    std::optional<std::string> norm;    // fit.norm: "minimax"; a least-squares fit's block has none
    std::optional<std::string> certify; // fit.certify: "samples" or "cells"
    std::optional<std::string> epsText; // fit.eps_arg: eps as it was typed ("2%")
    std::optional<std::string> cacheKey;
    std::optional<fit::PatientAxes> patientAxes; // source.patient_axes: the grid's directions in LPS
    std::optional<float> backgroundFill;         // background_fill: what omitted cells stand for
    std::optional<int> frame;                    // source.frame: which frame of a 4D file
    std::uint64_t nonFiniteSamples = 0;          // source.non_finite_samples: NaN/Inf samples (no data)
};

FitMetaView readFitMeta(const std::string& metaJson);

} // namespace vots::meta
