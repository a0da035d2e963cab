// Server: wires the parts together, installs the routes and the guards every request passes through.
#include "vots/server/Server.h"

#include "ServerImpl.h"
#include "frames/RenderFrames.h"
#include "routes/HttpJson.h"
#include "routes/StaticFiles.h"

#include "vots/fit/MemoryBudget.h"

#include <sys/socket.h>

#include <algorithm>
#include <chrono>
#include <iostream>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t MAX_BODY_BYTES = 64 * 1024; // POST bodies (a fit request is ~100 bytes)
constexpr std::size_t MAX_TARGET_CHARS = 4096;    // httplib itself answers 414 above 8192
// Debian's httplib is a compiled library that listens with a backlog of 5 (CPPHTTPLIB_LISTEN_BACKLOG
// only changes it when httplib is built with the define). With one request per connection, many clients
// at once overflow that queue, and a dropped SYN is sent again only after seconds.
constexpr int LISTEN_BACKLOG = 1024;
// Cache files are written in pauses this long without frames or requested fits: a user moving the eps
// slider again at once would otherwise share the cores with the last fit's file.
constexpr auto DISK_WRITE_QUIET = std::chrono::milliseconds(500);

FitJobLimits limitsFrom(const ServerOptions& o, std::uint64_t memoryBudget) {
    FitJobLimits limits;
    limits.boxCacheBytes = std::min(o.boxCacheBytes, memoryBudget / 4);
    limits.maxRunning = o.maxRunningFits;
    limits.maxQueued = o.maxQueuedFits;
    limits.warmUp = o.warmUpFits;
    limits.perClient = o.maxFitsPerClient;
    return limits;
}

bool isApiPath(const std::string& path) {
    return path.rfind("/api/", 0) == 0 || path == "/api" || path == "/render" || path == "/turntable";
}

httplib::Server::HandlerResponse refuse(httplib::Response& res, const Refusal& refusal) {
    if (refusal.status == 401) res.set_header("WWW-Authenticate", "Bearer");
    sendError(res, refusal.status, refusal.message);
    return httplib::Server::HandlerResponse::Handled;
}

std::optional<Refusal> screenTarget(const httplib::Request& req) {
    if (req.target.size() > MAX_TARGET_CHARS) return Refusal{414, "request target too long"};
    if (isHostileTarget(req.target) || req.path.find('\0') != std::string::npos)
        return Refusal{400, "path-like or encoded characters ('..', backslash, NUL) are not accepted"};
    return std::nullopt;
}

// listen() again on a listening socket only changes its backlog (Linux, BSD).
void raiseListenBacklog(const Server::Impl& s) {
    const int sock = s.listenSocket.load();
    if (sock >= 0) ::listen(sock, LISTEN_BACKLOG);
}

} // namespace

std::optional<Refusal> screenApiRequest(const Server::Impl& s, const httplib::Request& req) {
    if (auto refused = screenTarget(req)) return refused;
    if (auto refused = s.guard.checkHost(req)) return refused;
    return s.guard.checkApi(req);
}

Server::Impl::Impl(ServerOptions opts)
    : options(std::move(opts)),
      memory(options.memoryBudgetBytes ? options.memoryBudgetBytes : fit::defaultMemoryBudget()),
      registry(options.dataDirs, memory, options.heldFrameBytes),
      cache(options.cacheDir, options.memoryCacheBytes, options.diskCacheBytes),
      fitJobs(cache, stats, foreground, memory, limitsFrom(options, memory.budget())),
      seriesOpens(options.dicomWebServices,
                  options.cacheDir.empty() ? fs::path() : options.cacheDir / "dicomweb",
                  options.retrievedSeriesBytes, registry, memory),
      frames(options.frameCacheBytes),
      // As many again wait their turn: the users or views behind one address are queued, not refused.
      renders(options.maxRendersPerClient, "renders", options.maxRendersPerClient),
      guard(options.allowedHosts, options.accessTokens),
      tls(options.tlsCertificate.empty() && options.tlsKey.empty()
              ? nullptr
              : std::make_unique<TlsContext>(options.tlsCertificate, options.tlsKey)),
      http(tls.get()) {
    if (options.withRenderer)
        renderQueue = std::make_unique<RenderQueue>(stats, foreground, options.ranks.get());
    // Under mpirun the samples stay with the ranks, each reading its slab: this process holds none.
    if (options.ranks) registry.summarizeOnRanks(options.ranks.get());
    if (options.ranks && renderQueue)
        fitJobs.fitOnRanksThrough(
            [this](const Dataset& dataset, const FitKey& key, const fit::FitProgress& progress) {
                return fitOnRanks(*this, dataset, key, progress);
            });
    // Under mpirun the ranks hold the fits and upload them with their first frame.
    if (renderQueue && !options.ranks)
        fitJobs.uploadFitsThrough([this](const Dataset& dataset, std::shared_ptr<const fit::VotSpace> space) {
            uploadAhead(*this, dataset, std::move(space), false);
        });
    cache.deferDiskWritesWhile([this] { return foreground.busyWithin(DISK_WRITE_QUIET); });
    if (!options.auditLog.empty())
        audit = std::make_unique<AuditLog>(options.auditLog, options.auditLogBytes);
}

std::vector<fs::path> defaultDataDirs() {
    std::vector<fs::path> dirs;
    std::error_code ec;
    if (fs::is_directory("data", ec)) dirs.emplace_back("data");
    return dirs;
}

fs::path defaultWebDir() {
    std::error_code ec;
    if (fs::is_directory("web", ec)) return "web";
    // Installed, bin/vots finds share/vots/web; the build tree links the same place to the source's web/.
    const fs::path beside = fs::read_symlink("/proc/self/exe", ec).parent_path() / VOTS_WEB_DIR_FROM_BIN;
    if (!ec && fs::is_directory(beside, ec)) return beside.lexically_normal();
    return {};
}

Server::Server(ServerOptions options) : mImpl(std::make_unique<Impl>(std::move(options))) {
    Impl& s = *mImpl;
    GatedHttpServer& http = s.http;
    ConnectionLimits connections;
    connections.workerThreads = std::max(4, s.options.httpThreads);
    connections.maxStreams = static_cast<std::size_t>(std::max(1, s.options.maxEventStreams));
    connections.gate.maxBodyBytes = MAX_BODY_BYTES;
    http.trustProxy(s.options.trustedProxy);
    http.startConnections(connections);
    http.set_payload_max_length(MAX_BODY_BYTES);
    // One request per connection (GatedHttpServer answers each with Connection: close): a kept-alive
    // connection would have to go back through the gate anyway, and reconnecting on loopback is cheap.
    http.set_keep_alive_max_count(1);
    // Browsers that have seen the server over HTTPS never try it over plain HTTP again (a year).
    if (s.tls) http.set_default_headers({{"Strict-Transport-Security", "max-age=31536000"}});
    http.set_socket_options([&s](socket_t sock) {
        httplib::default_socket_options(sock);
        s.listenSocket = sock;
    });

    // Every request passes here first: hostile targets and foreign Host names are refused before any
    // route sees them, API requests pass the token and cross-site checks, and other paths are static files.
    http.set_pre_routing_handler([&s](const httplib::Request& req, httplib::Response& res) {
        if (isApiPath(req.path)) {
            if (const auto refused = screenApiRequest(s, req)) return refuse(res, *refused);
            // Never serve patient data unaudited.
            if (s.audit && auditAction(req.method, req.path) && !s.audit->ready())
                return refuse(res,
                              Refusal{503, "the audit log cannot be written; data requests are refused"});
            return httplib::Server::HandlerResponse::Unhandled;
        }
        if (const auto refused = screenTarget(req)) return refuse(res, *refused);
        if (const auto refused = s.guard.checkHost(req)) return refuse(res, *refused);
        // The viewer's own files need no token: they hold nothing secret, and the page has to load to
        // read the token from its URL.
        if (req.method != "GET" && req.method != "HEAD") {
            sendError(res, 405, "static files are GET only");
            return httplib::Server::HandlerResponse::Handled;
        }
        if (!serveStatic(s, req, res)) sendError(res, 404, "not found: " + req.path.substr(0, 200));
        return httplib::Server::HandlerResponse::Handled;
    });
    // Any 4xx/5xx without a body (httplib's own 404, 413, 414, ...) gets a JSON one.
    const httplib::Server::HandlerWithResponse onError = [](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        sendError(res, res.status, statusText(res.status));
        return httplib::Server::HandlerResponse::Handled;
    };
    http.set_error_handler(onError);
    if (s.audit)
        http.set_logger([&s](const httplib::Request& req, const httplib::Response& res) {
            if (const auto action = auditAction(req.method, req.path))
                s.audit->write(auditLine(*action, req, res, s.guard.tokenOf(req)));
        });
    http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        sendException(res, error);
    });

    installDatasetRoutes(s);
    installStatsRoute(s);
    installAccessRoute(s);
    installRenderRoute(s);
    installTurntableRoute(s);
    installJobRoutes(s);
    installPacsRoutes(s);
    installPacsStoreRoute(s);
    s.viewers = std::make_unique<ViewerStreams>(s);
    http.takeUpgrades(isViewerStreamRequest,
                      [&s](ArrivedRequest request) { s.viewers->adopt(std::move(request)); });

    const std::vector<std::string> names = s.registry.names();
    const std::string& startup = s.options.startupDataset;
    if (std::find(names.begin(), names.end(), startup) != names.end())
        s.readyingStartup = std::thread([&s] { readyStartupDataset(s, s.options.startupDataset); });
    else if (!startup.empty())
        std::cerr << "vots serve: no dataset '" << startup.substr(0, 200)
                  << "' in the data folders to prepare; nothing prepared\n";
}

Server::~Server() {
    stop();
    if (mImpl->readyingStartup.joinable())
        mImpl->readyingStartup.join(); // fits are answered by stop(); a frame is short
}

bool Server::bindToPort(const std::string& host, int port) {
    if (!mImpl->http.bind_to_port(host, port)) return false;
    mImpl->guard.bound(host, port);
    raiseListenBacklog(*mImpl);
    return true;
}
int Server::bindToAnyPort(const std::string& host) {
    const int port = mImpl->http.bind_to_any_port(host);
    if (port > 0) {
        mImpl->guard.bound(host, port);
        raiseListenBacklog(*mImpl);
    }
    return port;
}

void Server::reloadTls() {
    if (mImpl->tls) mImpl->tls->reload();
}

bool Server::servesTls() const {
    return mImpl->tls != nullptr;
}

bool Server::listenAfterBind() {
    return mImpl->http.listenUntilStopped();
}
std::uint64_t Server::memoryBudget() const {
    return mImpl->memory.budget();
}

bool Server::isRunning() const {
    return mImpl->http.is_running();
}

void Server::stop() {
    mImpl->fitJobs.shutdown(); // handlers waiting on fits are answered at once
    mImpl->http.stopListening();
    mImpl->http.stopConnections(); // waiting connections closed, running handlers and streams joined
    if (mImpl->viewers) mImpl->viewers->stop(); // sockets closed, their draws finished
}

std::string Server::rendererSummary() const {
    const auto& queue = mImpl->renderQueue;
    if (!queue) return "renderer disabled";
    if (!queue->hasContext()) return "no renderer (/render answers 503): " + queue->contextError();
    return "renderer: " + queue->rendererName();
}

} // namespace vots::server
