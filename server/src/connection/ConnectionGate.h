// ConnectionGate: holds accepted connections in one epoll loop until their request has arrived, so that
// idle clients and slow senders wait without a worker thread (docs/RELIABILITY.md, "Hostile connections").
#pragma once

#include "connection/TlsContext.h"

#include <atomic>
#include <chrono>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace vots::server {

/// A connection whose request head (and body, up to GateLimits::maxBodyBytes) has arrived. The fd is
/// blocking again and belongs to whoever receives this.
struct ArrivedRequest {
    int fd = -1;
    std::string bytes; // everything read so far: head and body
    std::string method;
    std::string target;
    std::string peerAddress;
    int peerPort = 0;
    std::string localAddress;
    int localPort = 0;
    TlsSession tls; // HTTPS: the session, its handshake done (the fd is then non-blocking); else null
};

struct GateLimits {
    // A connection that sends nothing for this long is closed, like httplib's keep-alive timeout.
    std::chrono::milliseconds firstByte{5000};
    // Head and body must have arrived this long after the accept: a client sending a byte every few
    // seconds cannot keep a connection open for ever.
    std::chrono::milliseconds wholeRequest{10000};
    std::size_t maxRequestLine = 8192; // httplib's CPPHTTPLIB_REQUEST_URI_MAX_LENGTH: longer is 414
    std::size_t maxHeadBytes = 64 * 1024;
    std::size_t maxHeaderLines = 100;
    std::size_t maxBodyBytes = 64 * 1024; // bodies up to this are read before dispatch; larger ones are
                                          // handed on at once so the handler can answer 413
    std::size_t maxConnections = 60000;   // waiting at once; beyond, the oldest waiting one is closed
};

/// Thread-safe. One thread; dispatch() runs on it and must only hand the request on.
class ConnectionGate {
public:
    using Dispatch = std::function<void(ArrivedRequest)>;
    /// tls: when not null, every connection is HTTPS: its handshake is done here too, without a thread.
    ConnectionGate(GateLimits limits, Dispatch dispatch, const TlsContext* tls = nullptr);
    ~ConnectionGate(); // stop()
    ConnectionGate(const ConnectionGate&) = delete;
    ConnectionGate& operator=(const ConnectionGate&) = delete;

    /// Takes ownership of an accepted socket (closed at once after stop()).
    void add(int fd);
    /// Closes every waiting connection and joins the thread; idempotent.
    void stop();
    /// Connections waiting for their request (or being drained after a refusal).
    std::size_t waiting() const { return mWaitingCount.load(); }

private:
    struct Connection {
        int fd = -1;
        std::chrono::steady_clock::time_point accepted;
        std::string bytes;
        bool draining = false;  // refused: the answer is sent, the rest of the request is read and dropped
        bool continued = false; // "100 Continue" sent for an "Expect: 100-continue" request
        TlsSession tls;         // HTTPS only
        bool handshaking = false;
        bool sniffed = false; // its first byte seen: a TLS record, not plain HTTP
    };
    enum class Handshake { Wait, Done, Failed, PlainHttp };
    enum class Verdict {
        Wait,
        WaitAfterContinue, // Expect: 100-continue and the body not there yet: say 100, then wait
        Dispatch,
        TooLongTarget,
        TooLargeHead,
        ChunkedBody // Transfer-Encoding: the API's bodies are small JSON with a Content-Length
    };

    void threadMain();
    void adopt(int fd);
    void readFrom(Connection& c);
    Handshake advanceHandshake(Connection& c);
    ssize_t receive(Connection& c, char* buffer, std::size_t size); // recv's contract, TLS or not
    void sendNow(Connection& c, std::string_view bytes);            // best effort, never blocks
    void watch(const Connection& c, bool writable);
    Verdict judge(const Connection& c) const;
    void dispatch(Connection& c);
    void refuse(Connection& c, int status, const char* message);
    void refuse(Connection& c, int status, const std::string& message);
    void sweep(std::chrono::steady_clock::time_point now);
    void close(int fd);

    const GateLimits mLimits;
    const Dispatch mDispatch;
    const TlsContext* const mTls;
    int mEpoll = -1;
    int mWake = -1; // eventfd: new sockets or stop
    std::mutex mMutex;
    std::vector<int> mIncoming;
    bool mStopped = false;
    std::map<int, Connection> mConnections; // gate thread only
    std::atomic<std::size_t> mWaitingCount{0};
    std::thread mThread;
};

} // namespace vots::server
