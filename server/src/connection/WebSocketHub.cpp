// WebSocketHub: Beast WebSocket sessions on one io_context thread: admission, bounded reads and sends,
// close codes for floods and broken frames.
#include "connection/WebSocketHub.h"

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>

#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <deque>
#include <map>
#include <mutex>
#include <thread>
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

void refuseUpgrade(int fd, int status, const std::string& message) {
    sendJsonErrorNow(fd, status, message);
    ::shutdown(fd, SHUT_RDWR);
    ::close(fd);
}

class Session;

} // namespace

struct WebSocketHub::State {
    State(WebSocketLimits l, Admit a, Open o) : limits(l), admit(std::move(a)), open(std::move(o)) {}

    const WebSocketLimits limits;
    const Admit admit;
    const Open open;
    std::atomic<std::size_t> openCount{0};
    std::mutex mutex; // all below but io: a session's last owner can be a draw thread, which then ends it
    bool stopped = false;
    std::map<Session*, std::weak_ptr<Session>> sessions;
    std::map<std::string, std::size_t> perAddress;
    // Last: destroyed first, with the handlers (and so the sessions) it still holds.
    net::io_context io{1};
    net::executor_work_guard<net::io_context::executor_type> work{io.get_executor()};
    std::thread thread;

    void adoptNow(ArrivedRequest request);
};

namespace {

class Session final : public WebSocketPeer, public std::enable_shared_from_this<Session> {
public:
    /// The hub has counted it (State::admitted) before it is made.
    Session(WebSocketHub::State& hub, tcp::socket socket, std::string address)
        : mHub(hub), mWs(beast::tcp_stream(std::move(socket))), mAddress(std::move(address)) {}
    ~Session() override {
        std::lock_guard lock(mHub.mutex);
        mHub.sessions.erase(this);
        if (--mHub.perAddress[mAddress] == 0) mHub.perAddress.erase(mAddress);
        --mHub.openCount;
    }

    void accept(http::request<http::empty_body> request, httplib::Request view) {
        mRequest = std::move(request);
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
                                beast::get_lowest_layer(self->mWs).close();
                                return;
                            }
                            if (!self->mOutgoing.empty()) self->mOutgoing.pop_front();
                            self->writeNext();
                        });
    }

    WebSocketHub::State& mHub;
    websocket::stream<beast::tcp_stream> mWs;
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
    const int fd = request.fd;
    http::request_parser<http::empty_body> parser;
    beast::error_code ec;
    parser.put(net::buffer(request.bytes), ec);
    if (ec || !parser.is_header_done()) return refuseUpgrade(fd, 400, "malformed upgrade request");
    const auto& head = parser.get();
    httplib::Request view;
    view.method = std::string(head.method_string());
    view.target = std::string(head.target());
    view.path = view.target.substr(0, view.target.find('?'));
    for (const auto& field : head)
        view.headers.emplace(std::string(field.name_string()), std::string(field.value()));
    view.remote_addr = request.peerAddress;
    view.remote_port = request.peerPort;
    if (const auto refused = admit(view)) return refuseUpgrade(fd, refused->status, refused->message);
    if (!websocket::is_upgrade(head))
        return refuseUpgrade(fd, 400, "this path takes a WebSocket upgrade only");
    tcp::socket socket(io);
    socket.assign(protocolOf(fd), fd, ec);
    if (ec) return refuseUpgrade(fd, 500, "cannot take over the socket");
    std::shared_ptr<Session> session;
    {
        std::lock_guard lock(mutex);
        const auto it = perAddress.find(request.peerAddress);
        if (openCount.load() >= limits.maxSockets ||
            (it != perAddress.end() && it->second >= limits.maxSocketsPerAddress)) {
            const bool full = openCount.load() >= limits.maxSockets;
            socket.release(ec); // the fd is ours again, to answer and close
            return refuseUpgrade(fd, full ? 503 : 429,
                                 full ? "too many viewer sockets open; try again later"
                                      : "too many viewer sockets from this address");
        }
        ++perAddress[request.peerAddress];
        ++openCount;
        session = std::make_shared<Session>(*this, std::move(socket), request.peerAddress);
        sessions[session.get()] = session;
    }
    session->accept(parser.release(), std::move(view));
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
    ::close(request.fd);
}

void WebSocketHub::stop() {
    {
        std::lock_guard lock(mState->mutex);
        if (mState->stopped) return;
        mState->stopped = true;
    }
    net::post(mState->io, [state = mState.get()] {
        std::vector<std::shared_ptr<Session>> open;
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
