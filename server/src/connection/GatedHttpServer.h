// GatedHttpServer: httplib's server with its connections taken over by a ConnectionGate: a worker thread
// sees a connection only once its request has arrived, and event streams run on their own threads
// (docs/RELIABILITY.md, "Hostile connections").
#pragma once

#include "connection/BufferedSocketStream.h"
#include "connection/ConnectionGate.h"
#include "connection/StreamThreads.h"
#include "connection/TlsContext.h"

#include <httplib.h>

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace vots::server {

struct ConnectionLimits {
    int workerThreads = 12;        // requests handled at once (event streams not counted)
    std::size_t maxStreams = 1000; // event streams at once; more are answered 503
    GateLimits gate;
};

class GatedHttpServer : public httplib::Server {
public:
    /// tls: when not null (it must outlive this), connections are HTTPS only.
    explicit GatedHttpServer(const TlsContext* tls = nullptr);
    ~GatedHttpServer() override; // stopConnections()

    /// Starts the gate and the workers; call once, before listen_after_bind().
    void startConnections(const ConnectionLimits& limits);
    /// After stopListening(): closes waiting connections, then waits for the handlers and streams running.
    void stopConnections();

    /// listen_after_bind() that stopListening() ends whenever it comes, even before listening has begun:
    /// httplib's own stop() does nothing until its accept loop runs, so a stop a moment earlier was lost
    /// and the loop then ran for ever (a SIGTERM right after `vots serve` printed its address hung it).
    /// Returns false at once after stopListening().
    bool listenUntilStopped();
    void stopListening();

    /// Requests for which isUpgrade(method, target) holds go to `take` (on the gate's thread: it must only
    /// hand them on) instead of a worker: the WebSocket upgrades. Call before listen_after_bind().
    void takeUpgrades(std::function<bool(const std::string&, const std::string&)> isUpgrade,
                      std::function<void(ArrivedRequest)> take);

    /// Requests from this address (a reverse proxy) are taken to come from the last address of their
    /// X-Forwarded-For (quotas, logs); empty: none trusted. Call before listen_after_bind().
    void trustProxy(std::string address) { mTrustedProxy = std::move(address); }

    std::size_t waitingConnections() const;
    std::size_t runningStreams() const;

private:
    // httplib calls this (through its task queue, which runs it at once on the accept thread) for every
    // accepted socket; the gate takes the socket over instead of a worker blocking on it.
    bool process_and_close_socket(socket_t sock) override;
    void route(ArrivedRequest request); // on the gate's thread: to a worker, or a stream thread
    void serve(const ArrivedRequest& request);
    void answerAndClose(std::shared_ptr<ArrivedRequest> request, int status, const std::string& message);

    const TlsContext* const mTls;
    std::string mTrustedProxy;
    std::mutex mMutex; // start and stop
    bool mStopped = false;
    std::mutex mListenMutex;
    bool mListenEntered = false; // inside listen_after_bind()
    bool mListenStopped = false;
    std::unique_ptr<httplib::ThreadPool> mWorkers;
    std::unique_ptr<StreamThreads> mStreams;
    // Its own lock: stopConnections() holds mMutex while it joins the gate thread, which routes.
    std::mutex mUpgradeMutex;
    std::function<bool(const std::string&, const std::string&)> mIsUpgrade;
    std::function<void(ArrivedRequest)> mTakeUpgrade;
    std::unique_ptr<ConnectionGate> mGate; // after the workers: stopped first, it feeds them
};

/// True for GET /api/jobs/{digits}/events (with or without a query): the answers that last.
bool isEventStreamRequest(const std::string& method, const std::string& target);

} // namespace vots::server
