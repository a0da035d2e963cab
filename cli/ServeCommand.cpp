// `vots serve`: options -> vots::server::Server, then serve until SIGINT/SIGTERM; no HTTP logic here.
#include "Commands.h"
#include "ConfigFileOption.h"
#include "FitNormOption.h"
#include "MemoryBudgetOption.h"
#include "ServeDicomWeb.h"

#include "vots/dist/mpi/MpiFrameRanks.h"
#include "vots/dist/mpi/MpiWorld.h"
#include "vots/fit/Error.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/server/Exposure.h"
#include "vots/server/RenderPolicy.h"
#include "vots/server/Server.h"

#include <CLI/CLI.hpp>

#include <pthread.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <iostream>
#include <memory>
#include <thread>

namespace vots::cli {
namespace {

namespace fs = std::filesystem;

struct ServeArgs {
    std::string host = "127.0.0.1";
    int port = 8080;
    std::vector<std::string> data;
    std::string web;
    std::string cacheDir = "data/cache";
    int frameCacheMb = 64;
    int heldFramesMb = 0; // 0: a quarter of the memory budget
    int cacheDirGb = 16;
    bool noWarmUp = false;
    std::string norm{fit::nameOf(fit::SERVE_FIT_NORM)};
    std::string prepare = "cranium"; // the viewer's first dataset when the data folders have it
    std::string tokenFile;
    std::string tlsCert, tlsKey;
    bool insecureHttp = false;
    std::string behindProxy;
    std::string auditLog;
    int auditLogMb = 64;
    std::vector<std::string> allowHosts;
    std::string memoryBudget; // empty: the default
    int rendersPerClient = server::ServerOptions{}.maxRendersPerClient;
    int fitsPerClient = server::ServerOptions{}.maxFitsPerClient;
    ServeDicomWebArgs dicomWeb;
    std::string config; // --config FILE: the options above that the command line leaves out
};

/// "host:port" as a URL writes it: an IPv6 address in brackets.
std::string urlAuthority(const std::string& host, int port) {
    const bool ipv6 = host.find(':') != std::string::npos && host.front() != '[';
    return (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

std::string joined(const std::vector<fs::path>& dirs) {
    std::string out;
    for (const auto& d : dirs)
        out += (out.empty() ? "" : ", ") + d.string();
    return out.empty() ? "(none)" : out;
}

/// Every open connection is a descriptor, and the default soft limit (1024) would refuse clients long
/// before the gate has any trouble holding them: raise it to the hard limit, which needs no privilege.
void raiseOpenFileLimit() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur >= limit.rlim_max) return;
    const rlim_t wanted = limit.rlim_max;
    limit.rlim_cur = wanted;
    if (::setrlimit(RLIMIT_NOFILE, &limit) != 0)
        std::cerr << "vots serve: cannot raise the open-file limit to " << wanted
                  << "; connections beyond the current limit will wait to be accepted\n";
}

/// What every rank's part takes from the server and the options: the memory budget's check of its
/// planes, and the .vots reader that restores the meta block's fields.
dist::RankSetup rankSetupOf(const ServeArgs& a) {
    dist::RankSetup setup;
    setup.planesOverBudget = [budget = a.memoryBudget](const std::string& path, std::uint64_t planes,
                                                       fit::SampleStorage storage) {
        return planesBudgetRefusal(path, std::nullopt, budget, "", planes, storage);
    };
    return setup;
}

/// Beyond loopback the token and the images would cross the network in clear: only with TLS, behind a
/// proxy that terminates it, or when the operator says so (--insecure-http, warned about).
void refuseCleartextBeyondLoopback(const ServeArgs& a) {
    if (server::isLoopbackHost(a.host) || !a.tlsCert.empty() || !a.behindProxy.empty()) return;
    if (!a.insecureHttp)
        throw fit::InputError(
            "serving on " + a.host +
            " beyond loopback needs HTTPS: give --tls-cert and --tls-key, or --behind-proxy "
            "ADDR for a reverse proxy that terminates TLS, or --insecure-http to serve in clear");
    std::cerr << "vots serve: warning: --insecure-http: the access token and the images cross the network "
                 "unencrypted\n";
}

void runServe(const ServeArgs& a) {
    const dist::MpiWorld& world = dist::MpiWorld::get();
    std::shared_ptr<dist::MpiFrameRanks> ranks;
    if (world.distributed()) ranks = std::make_shared<dist::MpiFrameRanks>(world, a.prepare, rankSetupOf(a));
    // However rank 0 leaves, the other ranks are let go, after the server (its render thread) is gone. With
    // a rank lost, finalizing MPI could wait for ever on a send still going to it (seen: the job ran on 30 s
    // after SIGTERM when Open MPI had noticed the death at once), so rank 0 then leaves unfinalized too.
    struct ReleaseRanks {
        dist::MpiFrameRanks* ranks;
        ~ReleaseRanks() {
            if (!ranks) return;
            ranks->releaseRanks();
            if (ranks->lostARank()) dist::MpiWorld::get().leaveUnfinalized();
        }
    } releaseRanks{ranks.get()};
    if (ranks && a.prepare.empty())
        throw fit::InputError("under mpirun, vots serve draws one dataset across the ranks: name it with "
                              "--prepare DATASET");
    raiseOpenFileLimit();
    server::ServerOptions options;
    for (const auto& d : a.data)
        options.dataDirs.emplace_back(d);
    if (options.dataDirs.empty()) options.dataDirs = server::defaultDataDirs();
    options.webDir = a.web.empty() ? server::defaultWebDir() : fs::path(a.web);
    options.cacheDir = a.cacheDir;
    options.frameCacheBytes = static_cast<std::size_t>(a.frameCacheMb) << 20;
    options.heldFrameBytes = static_cast<std::uint64_t>(a.heldFramesMb) << 20;
    options.diskCacheBytes = static_cast<std::uint64_t>(a.cacheDirGb) << 30;
    options.warmUpFits = !a.noWarmUp;
    options.fitNorm = fit::parseName<fit::FitNorm>(a.norm);
    options.startupDataset = a.prepare;
    options.allowedHosts = a.allowHosts;
    options.tlsCertificate = a.tlsCert;
    options.tlsKey = a.tlsKey;
    options.trustedProxy = a.behindProxy;
    options.auditLog = a.auditLog;
    options.auditLogBytes = static_cast<std::uint64_t>(a.auditLogMb) << 20;
    refuseCleartextBeyondLoopback(a);
    options.maxRendersPerClient = a.rendersPerClient;
    options.maxFitsPerClient = a.fitsPerClient;
    // Beyond loopback anyone on the network could read the images and start fits: a token is required,
    // the given one or else a fresh one, which only this process ever shows.
    const bool generatedToken = a.tokenFile.empty() && !server::isLoopbackHost(a.host);
    if (!a.tokenFile.empty()) options.accessTokens = server::readAccessTokenFile(a.tokenFile);
    if (generatedToken)
        options.accessTokens = {{"operator", server::Role::Operator, server::generateAccessToken()}};
    options.memoryBudgetBytes = resolveMemoryBudget(a.memoryBudget);
    options.dicomWebServices = dicomWebServicesOf(a.dicomWeb);
    options.retrievedSeriesBytes = static_cast<std::uint64_t>(a.dicomWeb.cacheGb) << 30;
    if (ranks) {
        options.ranks = ranks;
        // --prepare has each rank fit its own cells at the default eps (rank 0 fits nothing whole). The ranks
        // refit from box caches of their own, but the warm-up fits are one process's.
        options.warmUpFits = false;
    }

    // Signals are taken by sigwait below, so every thread the server starts must have them blocked.
    sigset_t stopSignals;
    sigemptyset(&stopSignals);
    sigaddset(&stopSignals, SIGINT);
    sigaddset(&stopSignals, SIGTERM);
    sigaddset(&stopSignals, SIGHUP); // not a stop: the TLS certificate and key are read again
    pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

    server::Server srv(options);
    int port = a.port;
    if (port == 0) {
        port = srv.bindToAnyPort(a.host);
        if (port < 0) throw fit::InputError("cannot listen on " + a.host + " (any port)");
    } else if (!srv.bindToPort(a.host, port)) {
        throw fit::InputError("cannot listen on " + a.host + ":" + std::to_string(port) +
                              " (in use, or not an address of this machine)");
    }
    const std::string url = (srv.servesTls() ? "https://" : "http://") + urlAuthority(a.host, port) + "/";
    std::cout << "vots serve: listening on " << url << "\n"
              << "  data:  " << joined(options.dataDirs) << "\n"
              << "  web:   " << (options.webDir.empty() ? "(none)" : options.webDir.string()) << "\n"
              << "  cache: " << options.cacheDir.string() << "\n"
              << "  token: "
              << (options.accessTokens.empty() ? "none (loopback only)"
                  : generatedToken             ? "required, generated (printed once on stderr)"
                                               : "required, from " + a.tokenFile)
              << "\n"
              << "  memory budget: " << fit::formatBytes(srv.memoryBudget())
              << (a.memoryBudget.empty() ? " (default: 80 % of the memory available)" : "") << "\n"
              << "  " << srv.rendererSummary() << "\n";
    for (const server::DicomWebService& pacs : options.dicomWebServices)
        std::cout << "  PACS " << pacs.name << ": " << pacs.endpoint.describe() << "\n";
    if (ranks)
        std::cout << "  ranks: " << world.size() << ", each frame of '" << a.prepare
                  << "' drawn from every rank's z cells and composited here\n";
    std::cout << std::flush;
    if (generatedToken)
        std::cerr << "vots serve: access token: " << options.accessTokens[0].token << "\n"
                  << "  send 'Authorization: Bearer TOKEN', or open the viewer at " << url
                  << "#token=" << options.accessTokens[0].token << std::endl;

    std::atomic<bool> stopping{false};
    std::thread listener([&srv, &stopping] {
        srv.listenAfterBind();
        // Listening ended by itself: wake the sigwait below. Not after srv.stop(): nobody waits for the
        // signal then, and under mpirun Open MPI's threads (started before the mask) would take it and end
        // the process before it lets the other ranks go.
        if (!stopping) ::kill(::getpid(), SIGTERM);
    });
    int signal = 0;
    while (sigwait(&stopSignals, &signal) == 0 && signal == SIGHUP) {
        try {
            srv.reloadTls();
            if (srv.servesTls()) std::cout << "vots serve: TLS certificate and key read again" << std::endl;
        } catch (const fit::InputError& e) {
            std::cerr << "vots serve: " << e.what() << "; the previous certificate stays in force"
                      << std::endl;
        }
    }
    std::cout << "vots serve: stopping" << std::endl;
    stopping = true;
    srv.stop();
    listener.join();
}

} // namespace

void addServeCommand(CLI::App& app) {
    auto args = std::make_shared<ServeArgs>();
    CLI::App* cmd =
        app.add_subcommand("serve", "Serve datasets, fits and MIP images over HTTP (see docs/API.md)");
    cmd->add_option("--host", args->host,
                    "Address to listen on (0.0.0.0: every interface). Any but loopback requires an access "
                    "token: the --token-file one, else one generated and printed once on stderr")
        ->capture_default_str();
    cmd->add_option("--port", args->port, "TCP port (0: any free port)")
        ->check(CLI::Range(0, 65535))
        ->capture_default_str();
    addConfigFileOption(*cmd, args->config);
    cmd->add_option(
        "--token-file", args->tokenFile,
        "File holding the access token (16..256 of A-Za-z0-9-._~+/=) that every API request must "
        "show as 'Authorization: Bearer TOKEN' or token=TOKEN; the viewer takes it from its "
        "URL's #token=TOKEN. Also asks for a token on loopback. Or lines 'NAME ROLE TOKEN', ROLE "
        "viewer (list, render, PACS search and retrieve) or operator (also fits and PACS stores)");
    cmd->add_option("--tls-cert", args->tlsCert,
                    "PEM certificate (chain) to serve HTTPS with (TLS 1.2 or newer); read again on SIGHUP")
        ->check(CLI::ExistingFile);
    cmd->add_option("--tls-key", args->tlsKey, "PEM private key of --tls-cert; read again on SIGHUP")
        ->check(CLI::ExistingFile);
    cmd->get_option("--tls-cert")->needs("--tls-key");
    cmd->get_option("--tls-key")->needs("--tls-cert");
    cmd->add_flag("--insecure-http", args->insecureHttp,
                  "Serve plain HTTP beyond loopback (the token and images cross the network in clear)");
    cmd->add_option(
        "--behind-proxy", args->behindProxy,
        "Address of a reverse proxy that terminates TLS: its requests are taken to come from "
        "the last X-Forwarded-For address (quotas); serving beyond loopback then needs no TLS here");
    cmd->add_option("--audit-log", args->auditLog,
                    "File to append one JSON line to per access to patient data (who, from where, which "
                    "dataset or study, what, the status); data requests get 503 while it cannot be written");
    cmd->add_option("--audit-log-mb", args->auditLogMb, "Size beyond which the audit log becomes FILE.1")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    cmd->add_option(
        "--allow-host", args->allowHosts,
        "Host name the server also answers to, as NAME (any port) or NAME:PORT (repeatable; "
        "e.g. a reverse proxy's name). Requests naming other hosts get 421, against DNS rebinding");
    cmd->add_option("--data", args->data, "Folder with volumes (repeatable); default ./data");
    cmd->add_option("--web", args->web,
                    "Folder with the web viewer; default ./web, else the binary's ../share/vots/web");
    cmd->add_option("--cache-dir", args->cacheDir, "Folder for fitted Vot-Spaces")->capture_default_str();
    cmd->add_option("--cache-dir-gb", args->cacheDirGb,
                    "GiB of .vots files kept in the cache folder; the least recently used are removed beyond "
                    "(the newest always stays)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
    cmd->add_option("--frame-cache-mb", args->frameCacheMb,
                    "Memory for rendered images answered again to identical /render requests (0: none)")
        ->check(CLI::Range(0, 65536))
        ->capture_default_str();
    cmd->add_option("--held-frames-mb", args->heldFramesMb,
                    "Memory for the loaded frames of 4D datasets other than frame 0; the least recently "
                    "used are dropped beyond it (0: a quarter of the memory budget)")
        ->check(CLI::Range(0, 1 << 24))
        ->capture_default_str();
    cmd->add_option("--prepare", args->prepare,
                    "Dataset to load, fit at its default eps and upload as the server starts, so the "
                    "viewer's first image is quick (skipped when the data folders lack it; '' for none)")
        ->capture_default_str();
    addMemoryBudgetOption(*cmd, args->memoryBudget);
    addServeDicomWebOptions(*cmd, args->dicomWeb);
    cmd->add_option(
           "--renders-per-client", args->rendersPerClient,
           "Renders one client (remote address; behind --behind-proxy its forwarded address) may have "
           "in progress; as many more wait their turn, and beyond those 429 (0: no limit)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
    cmd->add_option("--fits-per-client", args->fitsPerClient,
                    "New fits one client may have queued or running; more get 429 (0: no limit)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
    addFitNormOption(*cmd, args->norm);
    cmd->add_flag(
        "--no-warm-up", args->noWarmUp,
        "Do not fit the eps slider's steps near the last eps in idle time, which makes its moves cache hits");
    cmd->callback([args, cmd] {
        if (!args->config.empty()) applyConfigFile(*cmd, args->config);
        dist::MpiWorld& world = dist::MpiWorld::get();
        if (!world.distributed() || world.rank() == 0) return runServe(*args);
        try {
            // Rank 0 alone serves HTTP.
            dist::serveOtherRank(world, rankSetupOf(*args),
                                 [](render::VotRenderer& vots) { server::applyRenderPolicy(vots); });
        } catch (...) {
            world.leaveUnfinalized(); // rank 0 is gone, and messages to it may never complete
            throw;
        }
    });
}

} // namespace vots::cli
