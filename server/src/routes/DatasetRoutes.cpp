// GET /api/datasets: every volume and .vots file in the data folders with its kind, grid, value range,
// windows and defaults; what a .vots dataset cannot do.
#include "HttpError.h"
#include "ServerImpl.h"
#include "fits/EpsLadder.h"
#include "routes/HttpJson.h"

#include "vots/fit/MemoryBudget.h"
#include "vots/fit/PatientAxes.h"

#include <cmath>

namespace vots::server {
namespace {

nlohmann::json windowJson(const render::DisplaySettings& w) {
    return {{"level", w.level}, {"width", w.width}};
}

// The grid's directions in patient space (docs/API.md): null when the file says nothing.
template <class Grid> nlohmann::json orientationJson(const Grid& v) {
    if (!v.orientationKnown) return nullptr;
    nlohmann::json letters = nlohmann::json::array();
    for (const auto& axis : v.patientAxes) {
        const std::string name = fit::patientDirectionName(axis);
        letters.push_back(name.empty() ? nlohmann::json(nullptr) : nlohmann::json(name));
    }
    return {{"axes", v.patientAxes}, {"directions", letters}};
}

nlohmann::json datasetJson(const Dataset& d) {
    const auto window = render::windowForRange(d.range[0], d.range[1]);
    nlohmann::json presets = nlohmann::json::object();
    for (const auto& [name, preset] : d.presets)
        presets[name] = windowJson(preset);
    const bool isVots = d.kind == DatasetKind::Vots;
    nlohmann::json out = {{"name", d.name},
                          {"kind", std::string(fit::nameOf(d.kind))},
                          {"dims", isVots ? d.space->dims : d.volume->dims},
                          {"spacing", isVots ? d.space->spacing : d.volume->spacing},
                          {"orientation", isVots ? orientationJson(*d.space) : orientationJson(*d.volume)},
                          {"range", d.range},
                          {"window", windowJson(window)},
                          {"presets", presets},
                          {"defaultEps", d.defaultEps},
                          {"epsSteps", epsLadder(d)},
                          {"background", d.background},
                          {"modality", d.isCt ? "CT" : "other"},
                          {"frames", d.frames},
                          {"fits", true},
                          {"memoryNeeded", d.loadAndFitBytes}};
    if (isVots) {
        out["eps"] = d.space->eps; // the file's bound: the only one it can be drawn at
        out["votCount"] = d.space->vots.size();
    }
    return out;
}

// A dataset the memory budget refuses: what its header announces and why it is not loaded, so the
// viewer can show it greyed out with the reason instead of leaving it out.
nlohmann::json refusedJson(const std::string& name, DatasetKind kind,
                           const std::optional<fit::VolumeHeaderInfo>& header, const std::string& reason) {
    nlohmann::json out = {
        {"name", name}, {"kind", std::string(fit::nameOf(kind))}, {"fits", false}, {"error", reason}};
    if (header) {
        out["dims"] = header->dims;
        out["sourceType"] = fit::scalarTypeName(header->sourceType);
        out["memoryNeeded"] = fit::estimateLoadAndFitBytes(*header, DATASET_STORAGE);
    }
    return out;
}

} // namespace

float resolveEps(const Dataset& dataset, const EpsSpec& eps) {
    const auto value = static_cast<float>(eps.resolve(dataset.range[0], dataset.range[1]));
    if (!(value > 0.f) || !std::isfinite(value))
        throw HttpError(400, "eps resolves to " + std::to_string(value) + " for dataset '" + dataset.name +
                                 "' (its values are constant); give eps in data units");
    return value;
}

void refuseWhatVotsCannotDraw(const Dataset& dataset, const RenderParams& params) {
    if (dataset.kind != DatasetKind::Vots) return;
    if (params.renderer == render::RendererKind::Grid)
        throw HttpError(409, "dataset '" + dataset.name +
                                 "' is a Vot-Space file: renderer=grid (and mode=reference) needs the "
                                 "volume's grid, which it does not have; use renderer=vots");
    if (!params.epsGiven) return;
    // The viewer sends the eps /api/datasets gave it; a float that went through JSON and back may differ
    // in its last bit.
    const float asked = resolveEps(dataset, params.eps);
    const float own = dataset.space->eps;
    if (std::abs(asked - own) > 1e-6f * std::abs(own))
        throw HttpError(409, "dataset '" + dataset.name + "' is a Vot-Space file fitted at eps " +
                                 std::to_string(own) + ": another eps (" + std::to_string(asked) +
                                 ") needs a refit of the volume, which it does not have; omit eps");
}

void refuseFitOfVots(const Dataset& dataset) {
    if (dataset.kind == DatasetKind::Vots)
        throw HttpError(409, "dataset '" + dataset.name + "' is a Vot-Space file fitted at eps " +
                                 std::to_string(dataset.space->eps) +
                                 ": it cannot be refitted without its volume");
}

FitKey fitKeyFor(const Dataset& dataset, const EpsSpec& eps, int degree, fit::FitNorm norm) {
    FitKey key;
    key.dataset = dataset.name;
    key.frame = dataset.frame;
    key.eps = resolveEps(dataset, eps);
    key.degree = degree;
    key.norm = norm;
    key.background = dataset.background;
    key.volumeCrc = dataset.contentCrc;
    return key;
}

void installDatasetRoutes(Server::Impl& s) {
    s.http.Get("/api/datasets", [&s](const httplib::Request&, httplib::Response& res) {
        nlohmann::json list = nlohmann::json::array();
        const dist::FrameRanks* ranks = s.options.ranks.get();
        for (const std::string& name : s.registry.names()) {
            // Under mpirun only what the ranks draw is offered (and read, by them).
            if (ranks && !ranks->refusal(name, render::FrameRequest{}).empty()) continue;
            try {
                list.push_back(datasetJson(*s.registry.find(name))); // loads on first use
            } catch (const HttpError& e) {
                // Over the memory budget: listed as such. Any other file that does not load is left out
                // (and was logged once by the registry).
                if (e.status() == 507)
                    list.push_back(
                        refusedJson(name, s.registry.kind(name), s.registry.header(name), e.what()));
            }
        }
        sendJson(res, 200,
                 {{"datasets", list},
                  {"memoryBudget", s.memory.budget()},
                  {"memoryAvailable", s.memory.available()}});
    });
}

} // namespace vots::server
