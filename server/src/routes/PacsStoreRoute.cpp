// POST /api/pacs/{name}/store: the viewer's view as a slab sweep stored on that PACS (STOW-RS), a job
// polled at GET /api/pacs/stores/{id} that draws the slabs on the render thread, then stores them.
#include "HttpError.h"
#include "ServerImpl.h"
#include "dicomweb/PacsFailure.h"
#include "dicomweb/SearchAccess.h"
#include "frames/RenderFrames.h"
#include "routes/HttpJson.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/pacs/QidoSearch.h"
#include "vots/pacs/SpoolFolder.h"
#include "vots/pacs/StowStore.h"
#include "vots/render/Camera.h"
#include "vots/render/SlabSweep.h"
#include "vots/server/SweepSeries.h"

#include <cstdint>
#include <cstdio>

namespace vots::server {
namespace {

// A send is drawn while other clients' frames wait between its slabs: bound its pixels as a turntable's.
constexpr std::int64_t MAX_PIXELS = std::int64_t{360} * 512 * 512;

struct StoreRequest {
    RenderParams frame; // the first slab's frame without its slab: camera, size, mode, renderer, eps
    render::SlabSweepSpacing spacing;
};

/// The body: the /render parameters as JSON fields (strings, or numbers for eps and degree) plus the
/// numbers thickness and step in mm. Throws HttpError 400.
StoreRequest parseStoreRequest(const std::string& body) {
    const nlohmann::json json = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object()) throw HttpError(400, "body must be a JSON object");
    QueryParams query;
    for (const auto& item : json.items()) {
        const std::string& key = item.key();
        if (key == "thickness" || key == "step") continue;
        if (key == "slab" || key == "client")
            throw HttpError(400, "field '" + key + "' is not taken: a sweep places its own slabs");
        if (item.value().is_string())
            query.emplace(key, item.value().get<std::string>());
        else if (item.value().is_number())
            query.emplace(key, item.value().dump());
        else
            throw HttpError(400, "field '" + key.substr(0, 32) + "' must be a string");
    }
    StoreRequest r;
    r.frame = parseRenderParams(query);
    const auto number = [&](const char* name) {
        const auto it = json.find(name);
        if (it == json.end() || !it->is_number())
            throw HttpError(400, std::string("field '") + name + "' (a number of mm) is required");
        return it->dump();
    };
    const std::string spacing = number("thickness") + "," + number("step");
    try {
        r.spacing = render::parseSlabSweep(spacing);
    } catch (const fit::InputError& e) {
        throw HttpError(400, std::string("thickness, step: ") + e.what());
    }
    if (r.frame.mode == render::RenderMode::Density)
        throw HttpError(400, "a sweep draws mip, minip or aip; mode 'density' takes no slab");
    return r;
}

nlohmann::json storeJson(const SweepStoreSnapshot& s) {
    return {{"id", s.id},
            {"service", s.service},
            {"dataset", s.dataset},
            {"description", s.description},
            {"state", std::string(fit::nameOf(s.state))},
            {"drawn", s.drawn},
            {"total", s.total},
            {"stored", s.stored},
            {"status", s.errorStatus ? nlohmann::json(s.errorStatus) : nlohmann::json(nullptr)},
            {"error", s.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.error)}};
}

/// The sweep's slabs, checked before anything is drawn. Throws HttpError 400.
render::SlabSweepPlan planFor(const StoreRequest& r, const Dataset& dataset) {
    render::SlabSweepPlan plan;
    try {
        plan = render::planSlabSweep(r.spacing, r.frame.camera, render::sceneBounds(*dataset.volume),
                                     r.frame.width, r.frame.height);
    } catch (const fit::InputError& e) {
        throw HttpError(400, e.what());
    }
    const std::int64_t pixels = static_cast<std::int64_t>(plan.slabs.size()) * r.frame.width * r.frame.height;
    if (pixels > MAX_PIXELS)
        throw HttpError(400, std::to_string(plan.slabs.size()) + " slabs at " +
                                 std::to_string(r.frame.width) + "x" + std::to_string(r.frame.height) +
                                 " are more than " + std::to_string(MAX_PIXELS) +
                                 " pixels: a thicker step or a smaller size");
    return plan;
}

std::vector<std::string> spoolPaths(const pacs::SpoolFolder& spool, std::size_t count) {
    std::vector<std::string> paths;
    for (std::size_t k = 0; k < count; ++k) {
        char name[32];
        std::snprintf(name, sizeof name, "/%05zu.dcm", k);
        paths.push_back(spool.path() + name);
    }
    return paths;
}

/// The send: waits for the fit as /render does, draws each slab in data units on the render queue into a
/// series in a spool folder (removed however it ends), and stores it in one STOW-RS request.
SweepStoreJobs::Work sendWork(Server::Impl& s, const DicomWebService& service, StoreRequest request,
                              render::SlabSweepPlan plan, SweepSeriesSource source) {
    return [&s, &service, request = std::move(request), plan = std::move(plan),
            source = std::move(source)](const SweepStoreJobs::Update& update, const std::atomic<bool>& stop) {
        update([](SweepStoreSnapshot& snap) { snap.state = SweepStoreState::Drawing; });
        const PreparedRender prepared = prepareRender(s, request.frame, "pacs-store");
        const pacs::SpoolFolder spool;
        const std::vector<std::string> paths = spoolPaths(spool, plan.slabs.size());
        const auto drawSlab = [&](const render::SweepSlab& slab) {
            if (stop) throw HttpError(503, "server is stopping"); // or cancelled: the job says which
            RenderJob job = prepared.job;
            static_cast<render::FrameRequest&>(job.params) = render::sweepFrame(request.frame, slab);
            job.values = true;
            RenderResult drawn = s.renderQueue->render(std::move(job));
            return DrawnSlab{std::move(drawn.values), drawn.drawable};
        };
        writeSweepSeries(source, plan, paths, drawSlab, [&](std::size_t drawn) {
            update([&](SweepStoreSnapshot& snap) { snap.drawn = static_cast<int>(drawn); });
        });
        update([](SweepStoreSnapshot& snap) { snap.state = SweepStoreState::Storing; });
        const pacs::StoreReport report = pacs::storeInstances(service.endpoint, service.access, paths, &stop);
        update([&](SweepStoreSnapshot& snap) { snap.stored = report.stored; });
    };
}

/// The patient and study the sweep joins: the dataset's own DICOM files, already read once to load it, so
/// a failure is the server's (500).
fit::DicomIdentity sourceIdentity(const Dataset& dataset) {
    try {
        return fit::readDicomIdentity(dataset.path.string(), dataset.dicomSeries);
    } catch (const fit::InputError& e) {
        throw HttpError(500, "cannot read the identity of dataset '" + dataset.name + "': " + e.what());
    }
}

std::uint64_t storeIdFrom(const httplib::Request& req) {
    try {
        return std::stoull(req.matches[1].str());
    } catch (const std::exception&) { // out of range: no such send
        throw HttpError(404, "unknown sweep store");
    }
}

} // namespace

void installPacsStoreRoute(Server::Impl& s) {
    s.http.Post(R"(/api/pacs/([A-Za-z0-9_-]{1,64})/store)", [&s](const httplib::Request& req,
                                                                 httplib::Response& res) {
        const DicomWebService& service = s.seriesOpens.service(req.matches[1].str());
        StoreRequest request = parseStoreRequest(req.body);
        if (s.options.ranks) throw HttpError(409, "a sweep is sent from one process, not under mpirun");
        const auto dataset = s.registry.find(request.frame.dataset, request.frame.frame);
        if (dataset->kind != DatasetKind::Volume || !fit::isDicomFolder(dataset->path.string()))
            throw HttpError(409,
                            "dataset '" + dataset->name +
                                "' is not a DICOM series: a sweep stored on a PACS joins its source's study");
        render::SlabSweepPlan plan = planFor(request, *dataset);
        if (!s.renderQueue || !s.renderQueue->hasContext())
            throw HttpError(503, s.renderQueue ? "rendering is unavailable: " + s.renderQueue->contextError()
                                               : "rendering is disabled");
        SweepSeriesSource source{request.spacing, request.frame, dataset->range, sourceIdentity(*dataset)};
        // Asked now, so refused credentials or a service that is down cost one answer, not a sweep drawn
        // first: the smallest search the service answers.
        try {
            pacs::StudyQuery probe;
            probe.limit = 1;
            (void)pacs::searchStudies(service.endpoint, searchAccess(service), probe);
        } catch (...) {
            throw pacsFailure(std::current_exception());
        }
        SweepStoreSnapshot initial;
        initial.service = service.name;
        initial.dataset = dataset->name;
        initial.description = sweepSeriesDescription(source, plan);
        initial.total = static_cast<int>(plan.slabs.size());
        const SweepStoreSnapshot started = s.sweepStores.start(
            std::move(initial), sendWork(s, service, std::move(request), std::move(plan), std::move(source)));
        sendJson(res, 202, storeJson(started));
    });

    s.http.Get(R"(/api/pacs/stores/(\d{1,20}))", [&s](const httplib::Request& req, httplib::Response& res) {
        sendJson(res, 200, storeJson(s.sweepStores.snapshot(storeIdFrom(req))));
    });

    s.http.Post(R"(/api/pacs/stores/(\d{1,20})/cancel)",
                [&s](const httplib::Request& req, httplib::Response& res) {
                    sendJson(res, 200, storeJson(s.sweepStores.cancel(storeIdFrom(req))));
                });
}

} // namespace vots::server
