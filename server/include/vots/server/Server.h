// The Vots HTTP server: routes over a dataset registry, fit jobs, a Vot-Space cache and the render thread.
#pragma once

#include "vots/fit/Fitter.h"
#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"
#include "vots/server/Exposure.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace vots::dist {
class FrameRanks;
}

namespace vots::server {

/// A PACS the viewer may browse (`vots serve --dicomweb NAME=URL`): searched and retrieved from under NAME.
struct DicomWebService {
    std::string name; // a plain identifier: the API's and the viewer's name for it
    pacs::DicomWebEndpoint endpoint;
    pacs::DicomWebAccess access; // never logged or answered
};

struct ServerOptions {
    std::vector<std::filesystem::path> dataDirs;         // searched in order for volumes
    std::filesystem::path webDir;                        // static files; empty: none served
    std::filesystem::path cacheDir;                      // .vots cache; empty: memory only
    std::size_t memoryCacheBytes = std::size_t{1} << 30; // fitted Vot-Spaces kept in memory
    // The fitter's box caches (what makes a refit at a new eps quick), at most a quarter of the memory
    // budget; beyond, the least recently used dataset's go first (BoxCaches).
    std::uint64_t boxCacheBytes = std::uint64_t{1} << 30;
    std::uint64_t diskCacheBytes = std::uint64_t{16} << 30; // .vots files kept in cacheDir (LRU beyond)
    std::size_t frameCacheBytes = std::size_t{64} << 20;    // encoded /render answers kept in memory
    int maxRunningFits = 2;
    int maxQueuedFits = 8;
    // Fit the eps around the last one into the box cache while idle (WarmUpFits). Off unless asked
    // (`vots serve` asks unless --no-warm-up): an embedding program or a test pays no background fits.
    bool warmUpFits = false;
    // How every fit of the server accepts a box (`vots serve --fit-norm`, docs/DESIGN.md §3).
    fit::FitNorm fitNorm = fit::SERVE_FIT_NORM;
    int httpThreads = 12;       // requests handled at once; idle connections and event streams hold none
    int maxEventStreams = 1000; // /api/jobs/{id}/events streams open at once (a thread each); more: 503
    // Per client (remote address; behind a proxy every user is the proxy's one client): renders in
    // progress (as many more wait their turn) and fits queued or running that it started; more are
    // refused with 429.
    int maxRendersPerClient = 4;
    int maxFitsPerClient = 3;
    bool withRenderer = true; // false: never try EGL (tests of the 503 path)
    // Loaded, fitted at its default eps and uploaded as the server starts, when the data folders have
    // it: the viewer's first image then waits for none of that. Empty: none.
    std::string startupDataset;
    // Security (docs/API.md): Host names answered besides the bound address (and, bound to loopback, the
    // loopback names), as NAME (any port) or NAME:PORT; and the tokens, one of which every request but
    // the viewer's files must show, with its role (empty: none asked for, everyone an operator).
    std::vector<std::string> allowedHosts;
    std::vector<AccessToken> accessTokens;
    // HTTPS (`--tls-cert`, `--tls-key`): PEM certificate chain and key; both empty: plain HTTP.
    std::filesystem::path tlsCertificate, tlsKey;
    // `--audit-log FILE`: one JSON line per access to patient data; empty: none. Beyond auditLogBytes the
    // file becomes FILE.1 and a new one is begun.
    std::filesystem::path auditLog;
    std::uint64_t auditLogBytes = std::uint64_t{64} << 20;
    // `--behind-proxy ADDR`: requests from this address carry their client in X-Forwarded-For.
    std::string trustedProxy;
    // Loads and fits are refused (507) when their estimate from the header exceeds the budget minus the
    // process's resident memory: never an allocation the kernel kills the server for. 0: the default,
    // fit::defaultMemoryBudget() (80 % of the memory available at start).
    std::uint64_t memoryBudgetBytes = 0;
    // Frames of 4D datasets other than frame 0 stay loaded within this many bytes (their samples), least
    // recently used dropped first (and before a load the memory budget would refuse). 0: a quarter of the
    // memory budget.
    std::uint64_t heldFrameBytes = 0;
    // Under mpirun (dist/mpi's MpiFrameRanks): frames and fits are made through it on every rank, the
    // frames composited; what it refuses is answered 409. Null: frames are drawn here alone.
    std::shared_ptr<dist::FrameRanks> ranks;
    // PACS to browse (docs/PACS.md); retrieved series are kept in cacheDir/dicomweb (a temporary folder
    // when cacheDir is empty) within retrievedSeriesBytes (--dicomweb-cache-gb), least recently opened
    // removed first.
    std::vector<DicomWebService> dicomWebServices;
    std::uint64_t retrievedSeriesBytes = std::uint64_t{16} << 30;
};

/// The folders `vots serve` uses when none are given: ./data (where scripts/fetch-ct puts the Cranium)
/// when present.
std::vector<std::filesystem::path> defaultDataDirs();
/// ./web when present, else ../share/vots/web beside the executable when present (installed, or the
/// build tree's link to the source's web/), else empty.
std::filesystem::path defaultWebDir();

class Server {
public:
    explicit Server(ServerOptions options); // starts the render thread and fit workers
    ~Server();                              // stop()s, then joins everything
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    /// Binds; returns false (bindToPort) or -1 (bindToAnyPort) on failure.
    bool bindToPort(const std::string& host, int port);
    int bindToAnyPort(const std::string& host);
    /// Serves until stop(), whenever that comes (false at once after it); blocks the calling thread.
    bool listenAfterBind();
    void stop();
    bool isRunning() const;

    /// HTTPS: reads the certificate and key again for the connections that follow; throws
    /// fit::InputError (the old ones stay in force) when they cannot be read. Nothing for plain HTTP.
    void reloadTls();
    bool servesTls() const;

    /// The memory budget in force (the option, or the default it resolved to).
    std::uint64_t memoryBudget() const;

    /// One line about the renderer ("llvmpipe ..." or why there is none).
    std::string rendererSummary() const;

    struct Impl;

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace vots::server
