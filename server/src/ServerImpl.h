// Server internals shared by the route files: the parts a request touches, in construction order.
#pragma once

#include "ServerStats.h"
#include "connection/ClientQuota.h"
#include "connection/GatedHttpServer.h"
#include "datasets/DatasetRegistry.h"
#include "datasets/MemoryAdmission.h"
#include "dicomweb/SeriesOpenJobs.h"
#include "dicomweb/SweepStoreJobs.h"
#include "fits/FitJobs.h"
#include "fits/VotSpaceCache.h"
#include "frames/ForegroundActivity.h"
#include "frames/FrameCache.h"
#include "frames/RenderQueue.h"
#include "routes/Params.h"
#include "security/AuditLog.h"
#include "security/RequestGuard.h"
#include "stream/ViewerStreams.h"
#include "vots/server/Server.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <atomic>
#include <memory>
#include <string>
#include <thread>

namespace vots::server {

struct Server::Impl {
    explicit Impl(ServerOptions opts);

    ServerOptions options;
    ServerStats stats;
    ForegroundActivity foreground; // frames and requested fits, which background work waits for
    MemoryAdmission memory;        // --memory-budget: loads and fit jobs are admitted against it
    DatasetRegistry registry;
    VotSpaceCache cache;
    FitJobs fitJobs;
    SeriesOpenJobs seriesOpens;               // PACS series opened as datasets, kept in cacheDir/dicomweb
    std::unique_ptr<RenderQueue> renderQueue; // null when options.withRenderer is false
    SweepStoreJobs sweepStores;               // slab sweeps sent to a PACS; their frames use renderQueue
    FrameCache frames;                        // encoded /render answers
    ClientQuota renders;                      // /render and /turntable requests in progress per client
    RequestGuard guard;                       // Host, token and cross-site checks before any route
    std::unique_ptr<AuditLog> audit;          // --audit-log; null without
    std::atomic<int> listenSocket{-1};        // the socket httplib binds, so its backlog can be raised
    std::thread readyingStartup;            // readyStartupDataset(options.startupDataset); joined by ~Server
    std::unique_ptr<ViewerStreams> viewers; // GET /api/stream's sockets; after the parts their frames use
    std::unique_ptr<TlsContext> tls;        // HTTPS; null for plain HTTP
    GatedHttpServer http;                   // destroyed first: no handler runs after the rest is gone
};

// Route installers, one file each.
void installDatasetRoutes(Server::Impl& s);  // GET /api/datasets
void installStatsRoute(Server::Impl& s);     // GET /api/stats
void installAccessRoute(Server::Impl& s);    // GET /api/access
void installRenderRoute(Server::Impl& s);    // GET /render
void installTurntableRoute(Server::Impl& s); // GET /turntable
void installJobRoutes(Server::Impl& s);      // POST /api/fit, GET /api/jobs/{id}, GET /api/jobs/{id}/events
void installPacsRoutes(Server::Impl& s);     // /api/pacs: searches and the opens of series
void installPacsStoreRoute(Server::Impl& s); // POST /api/pacs/{name}/store, GET /api/pacs/stores/{id}
/// The checks an API request passes before its route (target 414/400, Host 421, token 401, cross-site
/// 403, JSON 415): the pre-routing handler's for API paths, and the viewer socket's at its upgrade.
std::optional<Refusal> screenApiRequest(const Server::Impl& s, const httplib::Request& req);
/// Static files from the web folder, answered in the pre-routing step for non-API paths.
bool serveStatic(const Server::Impl& s, const httplib::Request& req, httplib::Response& res);

/// Loads the dataset, fits it at its default eps and draws a small frame of it (the upload), so the
/// viewer's first image waits for none of them; failures are logged and left to the first request.
void readyStartupDataset(Server::Impl& s, const std::string& name);

/// Resolved eps for a dataset, or HttpError 400 when it comes out 0 (a constant volume with "N%").
float resolveEps(const Dataset& dataset, const EpsSpec& eps);
/// HttpError 409 for a /render a .vots dataset cannot draw: reference mode (it has no grid) or an eps
/// other than the file's (that would be a refit, and it has no volume).
void refuseWhatVotsCannotDraw(const Dataset& dataset, const RenderParams& params);
/// HttpError 409 for a fit (POST /api/fit) of a .vots dataset: it has no volume to fit.
void refuseFitOfVots(const Dataset& dataset);
/// The key of a uniform-eps fit of the dataset (no focus).
FitKey fitKeyFor(const Dataset& dataset, const EpsSpec& eps, int degree, fit::FitNorm norm);

/// The job's visible state as JSON (GET /api/jobs/{id}, SSE data).
nlohmann::json jobJson(const JobSnapshot& job);

} // namespace vots::server
