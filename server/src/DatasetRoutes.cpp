// GET /api/datasets: every volume in the data folders with its grid, value range, windows and defaults.
#include "HttpError.h"
#include "HttpJson.h"
#include "ServerImpl.h"

#include "vots/fit/MemoryBudget.h"
#include "vots/fit/PatientAxes.h"

namespace vots::server {
namespace {

nlohmann::json windowJson(const render::DisplaySettings& w) {
    return {{"level", w.level}, {"width", w.width}};
}

// The grid's directions in patient space (docs/API.md): null when the file says nothing.
nlohmann::json orientationJson(const fit::Volume& v) {
    if (!v.orientationKnown) return nullptr;
    nlohmann::json letters = nlohmann::json::array();
    for (const auto& axis : v.patientAxes) {
        const std::string name = fit::patientDirectionName(axis);
        letters.push_back(name.empty() ? nlohmann::json(nullptr) : nlohmann::json(name));
    }
    return {{"axes", v.patientAxes}, {"directions", letters}};
}

nlohmann::json datasetJson(const Dataset& d) {
    const fit::Volume& v = *d.volume;
    const auto window = render::windowForRange(d.range[0], d.range[1]);
    nlohmann::json presets = nlohmann::json::object();
    for (const auto& [name, preset] : d.presets)
        presets[name] = windowJson(preset);
    return {{"name", d.name},
            {"dims", v.dims},
            {"spacing", v.spacing},
            {"orientation", orientationJson(v)},
            {"range", d.range},
            {"window", windowJson(window)},
            {"presets", presets},
            {"defaultEps", d.defaultEps},
            {"background", d.background},
            {"modality", d.isCt ? "CT" : "other"},
            {"fits", true},
            {"memoryNeeded", d.loadAndFitBytes}};
}

// A dataset the memory budget refuses: what its header announces and why it is not loaded, so the
// viewer can show it greyed out with the reason instead of leaving it out.
nlohmann::json refusedJson(const std::string& name, const std::optional<fit::VolumeHeaderInfo>& header,
                           const std::string& reason) {
    nlohmann::json out = {{"name", name}, {"fits", false}, {"error", reason}};
    if (header) {
        out["dims"] = header->dims;
        out["sourceType"] = fit::scalarTypeName(header->sourceType);
        out["memoryNeeded"] = fit::estimateLoadAndFitBytes(*header);
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

FitKey fitKeyFor(const Dataset& dataset, const EpsSpec& eps, int degree) {
    FitKey key;
    key.dataset = dataset.name;
    key.eps = resolveEps(dataset, eps);
    key.degree = degree;
    key.background = dataset.background;
    key.volumeCrc = dataset.contentCrc;
    return key;
}

void installDatasetRoutes(Server::Impl& s) {
    s.http.Get("/api/datasets", [&s](const httplib::Request&, httplib::Response& res) {
        nlohmann::json list = nlohmann::json::array();
        for (const std::string& name : s.registry.names()) {
            try {
                list.push_back(datasetJson(*s.registry.find(name))); // loads on first use
            } catch (const HttpError& e) {
                // Over the memory budget: listed as such. Any other file that does not load is left out
                // (and was logged once by the registry).
                if (e.status() == 507) list.push_back(refusedJson(name, s.registry.header(name), e.what()));
            }
        }
        sendJson(res, 200,
                 {{"datasets", list},
                  {"memoryBudget", s.memory.budget()},
                  {"memoryAvailable", s.memory.available()}});
    });
}

} // namespace vots::server
