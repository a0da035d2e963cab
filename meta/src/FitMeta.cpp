// Writes and reads the meta JSON block of .vots files; the key names live only here.
#include "vots/meta/FitMeta.h"

#include "vots/fit/EnumNames.h"
#include "vots/fit/PatientAxes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#ifndef VOTS_VERSION
#define VOTS_VERSION "unknown"
#endif

namespace vots::meta {
namespace {

using fit::FitOptions;
using fit::FitStats;
using fit::FocusRegion;
using fit::PatientAxes;
using fit::Volume;

using json = nlohmann::ordered_json;

// JSON has no NaN or infinity; an absent value is null.
json finiteOrNull(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}

template <class T> std::optional<T> field(const json& j, const json::json_pointer& ptr) {
    if (!j.contains(ptr)) return std::nullopt;
    const json& v = j.at(ptr);
    if constexpr (std::is_same_v<T, std::string>) {
        if (v.is_string()) return v.get<std::string>();
    } else if constexpr (std::is_integral_v<T>) {
        if (v.is_number_integer() || v.is_number_unsigned()) return v.get<T>();
    } else {
        if (v.is_number()) return v.get<T>();
    }
    return std::nullopt;
}

// Three rows of three finite numbers spanning space, else nullopt (a foreign or damaged block renders as
// a file without orientation would).
std::optional<PatientAxes> patientAxesField(const json& j, const json::json_pointer& ptr) {
    if (!j.contains(ptr)) return std::nullopt;
    const json& rows = j.at(ptr);
    if (!rows.is_array() || rows.size() != 3) return std::nullopt;
    PatientAxes axes{};
    for (std::size_t a = 0; a < 3; ++a) {
        if (!rows[a].is_array() || rows[a].size() != 3) return std::nullopt;
        for (std::size_t c = 0; c < 3; ++c) {
            if (!rows[a][c].is_number()) return std::nullopt;
            axes[a][c] = rows[a][c].get<double>();
        }
    }
    return fit::normalizedPatientAxes(axes);
}

} // namespace

std::string buildFitMeta(const FitProvenance& r) {
    const Volume& vol = *r.volume;
    const auto range = vol.valueRange();
    const FitOptions& o = r.options;
    json focus = nullptr;
    if (o.focus)
        focus = {{"center_index", o.focus->centerIndex},
                 {"radius", o.focus->radius},
                 {"eps_focus", o.focus->epsFocus}};
    const FitStats& s = r.stats;
    json meta = {
        {"software", {{"name", "vots"}, {"version", VOTS_VERSION}}},
        {"source",
         {{"path", r.sourcePath},
          {"name", vol.name},
          {"dims", vol.dims},
          {"spacing", vol.spacing},
          {"origin", vol.origin},
          {"type", scalarTypeName(vol.sourceType)},
          {"value_range", {range[0], range[1]}}}},
        {"fit",
         {{"requested_degree", o.degree},
          {"eps", o.eps},
          {"eps_arg", r.epsText.empty() ? json(nullptr) : json(r.epsText)},
          {"background", o.background ? finiteOrNull(*o.background) : json(nullptr)},
          {"method", nameOf(o.method)},
          {"certify", nameOf(o.certify)},
          {"focus", focus},
          {"threads", o.threads},
          {"seconds", s.seconds}}},
        {"stats",
         {{"seconds", s.seconds},
          {"box_fits", s.boxFits},
          {"box_scans", s.boxScans},
          {"cache_hits", s.cacheHits},
          {"covered_cells", s.coveredCells},
          {"background_cells", s.backgroundCells},
          {"max_error", finiteOrNull(s.maxError)}}},
        {"max_error", finiteOrNull(r.maxError)},
    };
    // Only a minimax fit names its norm: a least-squares fit's file keeps the bytes it had before the norm
    // could be chosen.
    if (o.norm != fit::FitNorm::Lsq) {
        meta["fit"]["norm"] = nameOf(o.norm);
        meta["stats"]["minimax_fits"] = s.minimaxFits;
        meta["stats"]["minimax_scans"] = s.minimaxScans;
        meta["stats"]["minimax_accepted"] = s.minimaxAccepted;
        meta["stats"]["centred_accepted"] = s.centredAccepted;
    }
    // Only a volume whose file states its orientation gets the key: other files keep their bytes.
    if (vol.orientationKnown) meta["source"]["patient_axes"] = vol.patientAxes;
    // Only a 4D file's fit and a volume with NaN/Inf samples get these keys.
    if (r.frame) meta["source"]["frame"] = *r.frame;
    if (const std::size_t noData = vol.nonFiniteCount(); noData > 0)
        meta["source"]["non_finite_samples"] = noData;
    // Only a fit that left cells out has a fill; a reader without the key counts them as the threshold.
    if (r.backgroundFill && std::isfinite(*r.backgroundFill)) meta["background_fill"] = *r.backgroundFill;
    if (!r.cacheKey.empty()) meta["key"] = r.cacheKey;
    // File names need not be UTF-8; replace bad bytes rather than fail after a long fit.
    return meta.dump(-1, ' ', false, json::error_handler_t::replace);
}

FitMetaView readFitMeta(const std::string& metaJson) {
    FitMetaView view;
    const json j = json::parse(metaJson, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object()) return view;
    view.isJson = true;
    view.requestedDegree = field<int>(j, json::json_pointer("/fit/requested_degree"));
    view.fitSeconds = field<double>(j, json::json_pointer("/fit/seconds"));
    if (!view.fitSeconds) // the server's cache blocks before this schema: {"key", "fitSeconds", ...}
        view.fitSeconds = field<double>(j, json::json_pointer("/fitSeconds"));
    view.coveredCells = field<std::uint64_t>(j, json::json_pointer("/stats/covered_cells"));
    view.sourcePath = field<std::string>(j, json::json_pointer("/source/path"));
    view.method = field<std::string>(j, json::json_pointer("/fit/method"));
    view.norm = field<std::string>(j, json::json_pointer("/fit/norm"));
    view.certify = field<std::string>(j, json::json_pointer("/fit/certify"));
    view.epsText = field<std::string>(j, json::json_pointer("/fit/eps_arg"));
    view.cacheKey = field<std::string>(j, json::json_pointer("/key"));
    view.patientAxes = patientAxesField(j, json::json_pointer("/source/patient_axes"));
    view.frame = field<int>(j, json::json_pointer("/source/frame"));
    view.nonFiniteSamples =
        field<std::uint64_t>(j, json::json_pointer("/source/non_finite_samples")).value_or(0);
    // A float was written; anything outside float's range is damage (and would not convert).
    if (const auto fill = field<double>(j, json::json_pointer("/background_fill"));
        fill && std::abs(*fill) <= double{std::numeric_limits<float>::max()})
        view.backgroundFill = static_cast<float>(*fill);
    const auto radius = field<double>(j, json::json_pointer("/fit/focus/radius"));
    const auto epsFocus = field<double>(j, json::json_pointer("/fit/focus/eps_focus"));
    const json::json_pointer centre("/fit/focus/center_index");
    if (radius && epsFocus && j.contains(centre) && j.at(centre).is_array() && j.at(centre).size() == 3) {
        FocusRegion f;
        for (std::size_t a = 0; a < 3; ++a) {
            if (!j.at(centre)[a].is_number()) return view;
            f.centerIndex[a] = j.at(centre)[a].get<double>();
        }
        f.radius = *radius;
        f.epsFocus = static_cast<float>(*epsFocus);
        view.focus = f;
    }
    return view;
}

} // namespace vots::meta
