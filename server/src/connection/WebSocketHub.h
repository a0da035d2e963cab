// WebSocketHub: the server's WebSockets (Boost.Beast) on one Asio thread, so that an idle or slow socket
// costs no thread; upgrades arrive from the ConnectionGate and pass the same checks as any request.
#pragma once

#include "connection/ConnectionGate.h"
#include "security/RequestGuard.h"

#include <httplib.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace vots::server {

struct WebSocketLimits {
    std::size_t maxMessageBytes = 8 * 1024; // larger: closed with 1009
    int maxMessagesPerSecond = 240;         // more in one second: closed with 1008 (a mouse sends ~60-240)
    std::size_t maxSockets = 256;           // open at once; more are answered 503
    std::size_t maxSocketsPerAddress = 32;  // from one remote address; more are answered 429
    std::size_t maxQueuedSends = 16;        // messages waiting for a page that does not read: closed, 1008
    std::chrono::seconds handshakeTimeout{10};
    // Without a byte from the page for this long (half of it is a ping the browser answers itself), the
    // socket is closed: a vanished client does not hold one for ever.
    std::chrono::seconds idleTimeout{60};
};

/// The server's side of one socket, for the application; thread-safe, and harmless after the close.
class WebSocketPeer {
public:
    virtual ~WebSocketPeer() = default;
    virtual void sendText(std::string text) = 0;
    virtual void sendBinary(std::string bytes) = 0;
    /// Sends a close frame after the messages already queued.
    virtual void close(std::uint16_t code, std::string reason) = 0;
};

/// What the application does with one socket. Runs on the hub's thread: it must not block.
class WebSocketHandler {
public:
    virtual ~WebSocketHandler() = default;
    /// A whole text message, valid UTF-8, at most maxMessageBytes.
    virtual void onText(std::string text) = 0;
    /// The socket is closed (by either side, or it failed); no call follows.
    virtual void onClosed() = 0;
};

/// Thread-safe.
class WebSocketHub {
public:
    /// Admission of an upgrade request (the guard's checks); a refusal is answered as HTTP JSON.
    using Admit = std::function<std::optional<Refusal>(const httplib::Request&)>;
    /// The application's handler for an admitted socket; it should hold the peer weakly.
    using Open = std::function<std::shared_ptr<WebSocketHandler>(std::weak_ptr<WebSocketPeer>,
                                                                 const httplib::Request&)>;

    WebSocketHub(WebSocketLimits limits, Admit admit, Open open);
    ~WebSocketHub(); // stop()
    WebSocketHub(const WebSocketHub&) = delete;
    WebSocketHub& operator=(const WebSocketHub&) = delete;

    /// Takes over an arrived upgrade request (its fd); from any thread.
    void adopt(ArrivedRequest request);
    /// Closes every socket (1001) and joins the thread; idempotent. Later adopt() calls close the fd.
    void stop();
    std::size_t openSockets() const;

    struct State; // the sessions and the io_context (WebSocketHub.cpp)

private:
    std::shared_ptr<State> mState;
};

} // namespace vots::server
