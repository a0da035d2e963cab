// GatedHttpServer: hands accepted sockets to the gate and serves arrived requests on workers or streams.
#include "connection/GatedHttpServer.h"

#include "connection/ErrorAnswer.h"
#include "connection/RequestHead.h"

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <thread>

namespace vots::server {
namespace {

// A worker waits this long at most for the client to take (or send) more bytes, as httplib's own
// read and write timeouts.
constexpr auto SOCKET_TIMEOUT = std::chrono::seconds(5);

/// Runs each task at once on the thread that enqueues it: httplib's accept thread then only passes
/// sockets on to the gate.
class RunAtOnce final : public httplib::TaskQueue {
public:
    void enqueue(std::function<void()> fn) override { fn(); }
    void shutdown() override {}
};

void closeConnection(int fd) {
    // As httplib does: both directions, then close.
    ::shutdown(fd, SHUT_RDWR);
    ::close(fd);
}

} // namespace

bool isEventStreamRequest(const std::string& method, const std::string& target) {
    constexpr std::string_view prefix = "/api/jobs/", suffix = "/events";
    if (method != "GET") return false;
    const std::string_view path = std::string_view(target).substr(0, target.find('?'));
    if (path.size() <= prefix.size() + suffix.size() || path.substr(0, prefix.size()) != prefix ||
        path.substr(path.size() - suffix.size()) != suffix)
        return false;
    const std::string_view id = path.substr(prefix.size(), path.size() - prefix.size() - suffix.size());
    return std::all_of(id.begin(), id.end(),
                       [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

GatedHttpServer::GatedHttpServer(const TlsContext* tls) : mTls(tls) {
    new_task_queue = [] { return new RunAtOnce(); };
}

GatedHttpServer::~GatedHttpServer() {
    stopConnections();
}

void GatedHttpServer::startConnections(const ConnectionLimits& limits) {
    std::lock_guard lock(mMutex);
    if (mGate || mStopped) return;
    mWorkers =
        std::make_unique<httplib::ThreadPool>(static_cast<std::size_t>(std::max(1, limits.workerThreads)));
    mStreams = std::make_unique<StreamThreads>(limits.maxStreams);
    mGate = std::make_unique<ConnectionGate>(
        limits.gate, [this](ArrivedRequest r) { route(std::move(r)); }, mTls);
}

void GatedHttpServer::stopConnections() {
    std::lock_guard lock(mMutex);
    if (mStopped) return;
    mStopped = true;
    if (mGate) mGate->stop();
    if (mWorkers) mWorkers->shutdown(); // runs what is queued, then joins
    if (mStreams) mStreams->joinAll();  // streams end with their job, or at once once stop() has run
}

bool GatedHttpServer::listenUntilStopped() {
    {
        std::lock_guard lock(mListenMutex);
        if (mListenStopped) return false;
        mListenEntered = true;
    }
    const bool listened = listen_after_bind();
    std::lock_guard lock(mListenMutex);
    mListenEntered = false;
    return listened;
}

void GatedHttpServer::stopListening() {
    // Once inside listen_after_bind(), httplib marks itself running before its first accept; until then
    // its stop() would be a no-op, so wait for that mark (a few microseconds of thread start-up).
    for (;;) {
        {
            std::lock_guard lock(mListenMutex);
            mListenStopped = true;
            if (!mListenEntered || is_running()) break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    stop();
}

void GatedHttpServer::takeUpgrades(std::function<bool(const std::string&, const std::string&)> isUpgrade,
                                   std::function<void(ArrivedRequest)> take) {
    std::lock_guard lock(mUpgradeMutex);
    mIsUpgrade = std::move(isUpgrade);
    mTakeUpgrade = std::move(take);
}

std::size_t GatedHttpServer::waitingConnections() const {
    return mGate ? mGate->waiting() : 0;
}

std::size_t GatedHttpServer::runningStreams() const {
    return mStreams ? mStreams->running() : 0;
}

bool GatedHttpServer::process_and_close_socket(socket_t sock) {
    if (mGate)
        mGate->add(sock);
    else
        closeConnection(sock);
    return true;
}

void GatedHttpServer::route(ArrivedRequest request) {
    if (!mTrustedProxy.empty() && request.peerAddress == mTrustedProxy)
        if (auto client = forwardedClient(request.bytes)) request.peerAddress = std::move(*client);
    {
        std::lock_guard lock(mUpgradeMutex);
        if (mIsUpgrade && mIsUpgrade(request.method, request.target)) return mTakeUpgrade(std::move(request));
    }
    auto shared = std::make_shared<ArrivedRequest>(std::move(request));
    if (isEventStreamRequest(shared->method, shared->target)) {
        if (!mStreams->tryStart([this, shared] { serve(*shared); }))
            answerAndClose(shared, 503, "too many event streams open; try again later");
        return;
    }
    mWorkers->enqueue([this, shared] { serve(*shared); });
}

void GatedHttpServer::serve(const ArrivedRequest& request) {
    BufferedSocketStream stream(request, SOCKET_TIMEOUT);
    bool connectionClosed = false;
    // One request per connection, as before the gate: an answer ends with Connection: close.
    process_request(stream, true, connectionClosed, nullptr);
    stream.shutdownTls();
    closeConnection(request.fd);
}

void GatedHttpServer::answerAndClose(std::shared_ptr<ArrivedRequest> request, int status,
                                     const std::string& message) {
    if (!request->tls) {
        sendJsonErrorNow(request->fd, status, message);
        return closeConnection(request->fd);
    }
    // Through TLS the answer may have to wait for the socket: a worker writes it, not the gate's thread.
    mWorkers->enqueue([request, status, message] {
        BufferedSocketStream stream(*request, SOCKET_TIMEOUT);
        stream.write(jsonErrorAnswer(status, message));
        stream.shutdownTls();
        closeConnection(request->fd);
    });
}

} // namespace vots::server
