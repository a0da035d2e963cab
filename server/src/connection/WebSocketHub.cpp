// WebSocketHub: Beast WebSocket sessions on one io_context thread: admission, bounded reads and sends,
// close codes for floods and broken frames.
#include "connection/WebSocketHub.h"

#include "connection/ErrorAnswer.h"
#include "connection/TlsSocketStream.h"

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <openssl/err.h>
#include <openssl/ssl.h>

#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <deque>
#include <map>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace vots::server {
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

namespace {

using Clock = std::chrono::steady_clock;
// How long stop() lets the pages answer the close frames before the thread is stopped anyway.
constexpr auto STOP_GRACE = std::chrono::milliseconds(500);
constexpr std::uint16_t POLICY_CLOSE = 1008;
constexpr std::uint16_t UNSUPPORTED_CLOSE = 1003;
constexpr std::uint16_t GOING_AWAY_CLOSE = 1001;

void refuseUpgrade(const ArrivedRequest& request, int status, const std::string& message) {
    sendJsonErrorNow(request.fd, status, message, request.tls.get());
    if (request.tls) {
        SSL_shutdown(request.tls.get()); // close_notify, best effort
        ERR_clear_error();
    }
    ::shutdown(request.fd, SHUT_RDWR);
    ::close(request.fd);
}

} // namespace

struct WebSocketHub::State {
    State(WebSocketLimits l, Admit a, Open o) : limits(l), admit(std::move(a)), open(std::move(o)) {}

    const WebSocketLimits limits;
    const Admit admit;
    const Open open;
    std::atomic<std::size_t> openCount{0};
    std::mutex mutex; // all below but io: a session's last owner can be a draw thread, which then ends it
    bool stopped = false;
    std::map<WebSocketPeer*, std::weak_ptr<WebSocketPeer>> sessions;
    std::map<std::string, std::size_t> perAddress;
    // Last: destroyed first, with the handlers (and so the sessions) it still holds.
    net::io_context io{1};
    net::executor_work_guard<net::io_context::executor_type> work{io.get_executor()};
    std::thread thread;

    void adoptNow(ArrivedRequest request);
    /// Counts a socket from `address` in (its Session counts it out), or says why it is refused.
    std::optional<Refusal> countIn(const std::string& address);
    template <class Stream>
    void startSession(Stream stream, const std::string& address,
                      beast::http::request<beast::http::empty_body> head, httplib::Request view);
};

namespace {

/// Stream: beast::tcp_stream for plain HTTP, TlsSocketStream over HTTPS.
template <class Stream>
class Session final : public WebSocketPeer, public std::enable_shared_from_this<Session<Stream>> {
    using std::enable_shared_from_this<Session<Stream>>::shared_from_this;
    using std::enable_shared_from_this<Session<Stream>>::weak_from_this;

public:
    /// The hub has counted it (State::countIn) before it is made.
    Session(WebSocketHub::State& hub, Stream stream, std::string address)
        : mHub(hub), mWs(std::move(stream)), mAddress(std::move(address)) {}
    ~Session() override {
        std::lock_guard lock(mHub.mutex);
        mHub.sessions.erase(this);
        if (--mHub.perAddress[mAddress] == 0) mHub.perAddress.erase(mAddress);
        --mHub.openCount;
    }

    void accept(http::request<http::empty_body> request, httplib::Request view) {
        mRequest = std::move(request);
        if constexpr (std::is_same_v<Stream, beast::tcp_stream>)
            beast::get_lowest_layer(mWs).expires_never(); // the WebSocket's own timeouts below
        mWs.set_option(
            websocket::stream_base::timeout{mHub.limits.handshakeTimeout, mHub.limits.idleTimeout, true});
        mWs.set_option(websocket::stream_base::decorator(
            [](websocket::response_type& res) { res.set(http::field::server, "vots"); }));
        mWs.read_message_max(mHub.limits.maxMessageBytes);
        mWs.async_accept(mRequest, [self = shared_from_this(), view = std::move(view)](beast::error_code ec) {
            if (!ec) self->opened(view);
        });
    }

    void sendText(std::string text) override { post(Outgoing{std::move(text), false}); }
    void sendBinary(std::string bytes) override { post(Outgoing{std::move(bytes), true}); }
    void close(std::uint16_t code, std::string reason) override {
        net::post(mHub.io, [self = shared_from_this(), code, reason = std::move(reason)] {
            self->closeWith(code, reason);
        });
    }

private:
    struct Outgoing {
        std::string bytes;
        bool binary = false;
    };

    void opened(const httplib::Request& view) {
        mHandler = mHub.open(weak_from_this(), view);
        if (!mHandler) return closeWith(POLICY_CLOSE, "refused");
        read();
    }

    void read() {
        mWs.async_read(
            mBuffer, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->received(ec); });
    }

    void received(beast::error_code ec) {
        if (ec) return ended(); // closed by the page, a protocol error Beast answered (1009, 1007), or gone
        std::string text = beast::buffers_to_string(mBuffer.data());
        mBuffer.consume(mBuffer.size());
        if (!mClosing) {
            if (!mWs.got_text()) {
                closeWith(UNSUPPORTED_CLOSE, "binary messages are not accepted");
            } else if (flooding()) {
                closeWith(POLICY_CLOSE, "too many messages");
            } else if (mHandler) {
                mHandler->onText(std::move(text));
            }
        }
        read(); // after a close: until the page's close frame (or the timeout) ends the read
    }

    bool flooding() {
        const auto now = Clock::now();
        if (now - mWindowStart >= std::chrono::seconds(1)) {
            mWindowStart = now;
            mWindowCount = 0;
        }
        return ++mWindowCount > mHub.limits.maxMessagesPerSecond;
    }

    void ended() {
        if (mHandler) mHandler->onClosed();
        mHandler.reset();
        mOutgoing.clear();
    }

    void post(Outgoing message) {
        net::post(mHub.io, [self = shared_from_this(), message = std::move(message)]() mutable {
            if (self->mClosing) return;
            if (self->mOutgoing.size() >= self->mHub.limits.maxQueuedSends)
                return self->closeWith(POLICY_CLOSE, "the page does not read its messages");
            self->mOutgoing.push_back(std::move(message));
            self->writeNext();
        });
    }

    void closeWith(std::uint16_t code, const std::string& reason) {
        if (mClosing) return;
        mClosing = true;
        mCloseReason = websocket::close_reason(static_cast<websocket::close_code>(code), reason);
        writeNext();
    }

    // One write at a time (Beast's rule); the close frame goes after the queued messages.
    void writeNext() {
        if (mWriting) return;
        if (mOutgoing.empty()) {
            if (!mClosing || mCloseSent) return;
            mCloseSent = mWriting = true;
            mWs.async_close(mCloseReason,
                            [self = shared_from_this()](beast::error_code) { self->mWriting = false; });
            return;
        }
        mWriting = true;
        mWs.binary(mOutgoing.front().binary);
        mWs.async_write(net::buffer(mOutgoing.front().bytes),
                        [self = shared_from_this()](beast::error_code ec, std::size_t) {
                            self->mWriting = false;
                            if (ec) { // the read fails too and ends the session
                                beast::close_socket(beast::get_lowest_layer(self->mWs));
                                return;
                            }
                            if (!self->mOutgoing.empty()) self->mOutgoing.pop_front();
                            self->writeNext();
                        });
    }

    WebSocketHub::State& mHub;
    websocket::stream<Stream> mWs;
    const std::string mAddress;
    http::request<http::empty_body> mRequest;
    beast::flat_buffer mBuffer;
    std::shared_ptr<WebSocketHandler> mHandler;
    std::deque<Outgoing> mOutgoing;
    bool mWriting = false;
    bool mClosing = false;
    bool mCloseSent = false;
    websocket::close_reason mCloseReason;
    Clock::time_point mWindowStart{};
    int mWindowCount = 0;
};

tcp protocolOf(int fd) {
    sockaddr_storage addr{};
    socklen_t length = sizeof addr;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &length) == 0 && addr.ss_family == AF_INET6)
        return tcp::v6();
    return tcp::v4();
}

} // namespace

void WebSocketHub::State::adoptNow(ArrivedRequest request) {
    http::request_parser<http::empty_body> parser;
    beast::error_code ec;
    parser.put(net::buffer(request.bytes), ec);
    if (ec || !parser.is_header_done()) return refuseUpgrade(request, 400, "malformed upgrade request");
    const auto& head = parser.get();
    httplib::Request view;
    view.method = std::string(head.method_string());
    view.target = std::string(head.target());
    view.path = view.target.substr(0, view.target.find('?'));
    for (const auto& field : head)
        view.headers.emplace(std::string(field.name_string()), std::string(field.value()));
    view.remote_addr = request.peerAddress;
    view.remote_port = request.peerPort;
    if (const auto refused = admit(view)) return refuseUpgrade(request, refused->status, refused->message);
    if (!websocket::is_upgrade(head))
        return refuseUpgrade(request, 400, "this path takes a WebSocket upgrade only");
    tcp::socket socket(io);
    socket.assign(protocolOf(request.fd), request.fd, ec);
    if (ec) return refuseUpgrade(request, 500, "cannot take over the socket");
    // Each frame is a small header then its image: with Nagle's algorithm the image waits for the header's
    // delayed acknowledgement (up to 40 ms on Linux), a stall on every frame.
    socket.set_option(tcp::no_delay(true), ec);
    if (const auto refused = countIn(request.peerAddress)) {
        socket.release(ec); // the fd is ours again, to answer and close
        return refuseUpgrade(request, refused->status, refused->message);
    }
    // The session's stream: over HTTPS, the TLS session whose handshake the gate has done.
    if (request.tls)
        startSession(TlsSocketStream(std::move(socket), std::move(request.tls)), request.peerAddress,
                     parser.release(), std::move(view));
    else
        startSession(beast::tcp_stream(std::move(socket)), request.peerAddress, parser.release(),
                     std::move(view));
}

std::optional<Refusal> WebSocketHub::State::countIn(const std::string& address) {
    std::lock_guard lock(mutex);
    const auto it = perAddress.find(address);
    if (openCount.load() >= limits.maxSockets)
        return Refusal{503, "too many viewer sockets open; try again later"};
    if (it != perAddress.end() && it->second >= limits.maxSocketsPerAddress)
        return Refusal{429, "too many viewer sockets from this address"};
    ++perAddress[address];
    ++openCount;
    return std::nullopt;
}

template <class Stream>
void WebSocketHub::State::startSession(Stream stream, const std::string& address,
                                       http::request<http::empty_body> head, httplib::Request view) {
    auto session = std::make_shared<Session<Stream>>(*this, std::move(stream), address);
    {
        std::lock_guard lock(mutex);
        sessions[session.get()] = session;
    }
    session->accept(std::move(head), std::move(view));
}

WebSocketHub::WebSocketHub(WebSocketLimits limits, Admit admit, Open open)
    : mState(std::make_shared<State>(limits, std::move(admit), std::move(open))) {
    mState->thread = std::thread([state = mState.get()] { state->io.run(); });
}

WebSocketHub::~WebSocketHub() {
    stop();
}

void WebSocketHub::adopt(ArrivedRequest request) {
    {
        std::lock_guard lock(mState->mutex);
        if (!mState->stopped) {
            net::post(mState->io, [state = mState.get(), request = std::move(request)]() mutable {
                state->adoptNow(std::move(request));
            });
            return;
        }
    }
    ::close(request.fd); // the TLS session, if any, goes with the request
}

void WebSocketHub::stop() {
    {
        std::lock_guard lock(mState->mutex);
        if (mState->stopped) return;
        mState->stopped = true;
    }
    net::post(mState->io, [state = mState.get()] {
        std::vector<std::shared_ptr<WebSocketPeer>> open;
        {
            std::lock_guard lock(state->mutex);
            for (auto& [raw, weak] : state->sessions)
                if (auto session = weak.lock()) open.push_back(std::move(session));
        }
        for (const auto& session : open)
            session->close(GOING_AWAY_CLOSE, "the server stops");
        state->work.reset();
    });
    const auto deadline = Clock::now() + STOP_GRACE;
    while (mState->openCount.load() > 0 && Clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    mState->io.stop();
    mState->thread.join();
}

std::size_t WebSocketHub::openSockets() const {
    return mState->openCount.load();
}

} // namespace vots::server
