// ConnectionGate: an epoll loop that reads requests (and TLS handshakes) without blocking and hands on the
// complete ones.
#include "connection/ConnectionGate.h"

#include "connection/ErrorAnswer.h"
#include "connection/RequestHead.h"

#include <openssl/err.h>
#include <openssl/ssl.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <string_view>

namespace vots::server {
namespace {

using Clock = std::chrono::steady_clock;
// How long a refused connection is read and dropped before it is closed: closing a socket with unread
// bytes sends a reset, which can destroy the answer before the client has read it.
constexpr auto DRAIN_TIME = std::chrono::seconds(2);
constexpr int SWEEP_MS = 100;

void setBlocking(int fd, bool blocking) {
    const int flags = ::fcntl(fd, F_GETFL, 0);
    if (flags >= 0) ::fcntl(fd, F_SETFL, blocking ? flags & ~O_NONBLOCK : flags | O_NONBLOCK);
}

void addressOf(const sockaddr_storage& addr, std::string& text, int& port) {
    char buffer[INET6_ADDRSTRLEN] = {};
    if (addr.ss_family == AF_INET) {
        const auto& in = reinterpret_cast<const sockaddr_in&>(addr);
        ::inet_ntop(AF_INET, &in.sin_addr, buffer, sizeof buffer);
        port = ntohs(in.sin_port);
    } else if (addr.ss_family == AF_INET6) {
        const auto& in6 = reinterpret_cast<const sockaddr_in6&>(addr);
        ::inet_ntop(AF_INET6, &in6.sin6_addr, buffer, sizeof buffer);
        port = ntohs(in6.sin6_port);
    }
    text = buffer;
}

} // namespace

ConnectionGate::ConnectionGate(GateLimits limits, Dispatch dispatch, const TlsContext* tls)
    : mLimits(limits), mDispatch(std::move(dispatch)), mTls(tls) {
    mEpoll = ::epoll_create1(EPOLL_CLOEXEC);
    mWake = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (mEpoll < 0 || mWake < 0) throw std::runtime_error("cannot create the connection gate's epoll");
    epoll_event event{};
    event.events = EPOLLIN;
    event.data.fd = mWake;
    ::epoll_ctl(mEpoll, EPOLL_CTL_ADD, mWake, &event);
    mThread = std::thread([this] { threadMain(); });
}

ConnectionGate::~ConnectionGate() {
    stop();
    ::close(mWake);
    ::close(mEpoll);
}

void ConnectionGate::add(int fd) {
    {
        std::lock_guard lock(mMutex);
        if (!mStopped) {
            mIncoming.push_back(fd);
            ++mWaitingCount;
            const std::uint64_t one = 1;
            [[maybe_unused]] const ssize_t n = ::write(mWake, &one, sizeof one);
            return;
        }
    }
    ::close(fd);
}

void ConnectionGate::stop() {
    {
        std::lock_guard lock(mMutex);
        if (mStopped) return;
        mStopped = true;
        const std::uint64_t one = 1;
        [[maybe_unused]] const ssize_t n = ::write(mWake, &one, sizeof one);
    }
    mThread.join();
}

void ConnectionGate::threadMain() {
    std::array<epoll_event, 256> events;
    auto lastSweep = Clock::now();
    for (;;) {
        const int n = ::epoll_wait(mEpoll, events.data(), static_cast<int>(events.size()), SWEEP_MS);
        for (int i = 0; i < n; ++i) {
            const int fd = events[static_cast<std::size_t>(i)].data.fd;
            if (fd == mWake) {
                std::uint64_t count = 0;
                [[maybe_unused]] const ssize_t r = ::read(mWake, &count, sizeof count);
                std::vector<int> incoming;
                bool stopped = false;
                {
                    std::lock_guard lock(mMutex);
                    incoming.swap(mIncoming);
                    stopped = mStopped;
                }
                for (const int socket : incoming)
                    adopt(socket);
                if (stopped) {
                    for (auto& [socket, connection] : mConnections)
                        ::close(socket);
                    mConnections.clear();
                    mWaitingCount = 0;
                    return;
                }
                continue;
            }
            const auto it = mConnections.find(fd);
            if (it != mConnections.end()) readFrom(it->second);
        }
        const auto now = Clock::now();
        if (now - lastSweep >= std::chrono::milliseconds(SWEEP_MS)) {
            sweep(now);
            lastSweep = now;
        }
    }
}

void ConnectionGate::adopt(int fd) {
    if (mConnections.size() >= mLimits.maxConnections) {
        // The oldest waiting connection is the likeliest to be idle: a real client sends at once.
        const auto oldest = std::min_element(mConnections.begin(), mConnections.end(), [](auto& a, auto& b) {
            return a.second.accepted < b.second.accepted;
        });
        close(oldest->first);
    }
    setBlocking(fd, false);
    epoll_event event{};
    event.events = EPOLLIN | EPOLLRDHUP;
    event.data.fd = fd;
    if (::epoll_ctl(mEpoll, EPOLL_CTL_ADD, fd, &event) != 0) {
        ::close(fd);
        --mWaitingCount;
        return;
    }
    Connection& c = mConnections[fd];
    c.fd = fd;
    c.accepted = Clock::now();
    if (mTls) {
        c.tls = mTls->accept(fd);
        c.handshaking = true;
        if (!c.tls) close(fd);
    }
}

void ConnectionGate::watch(const Connection& c, bool writable) {
    epoll_event event{};
    event.events = EPOLLIN | EPOLLRDHUP | (writable ? EPOLLOUT : 0u);
    event.data.fd = c.fd;
    ::epoll_ctl(mEpoll, EPOLL_CTL_MOD, c.fd, &event);
}

ConnectionGate::Handshake ConnectionGate::advanceHandshake(Connection& c) {
    if (!c.sniffed) {
        // A TLS connection opens with a handshake record (type 22); anything else is most likely plain
        // HTTP sent to the HTTPS port, which is answered in plain HTTP so that the client learns why.
        unsigned char first = 0;
        const ssize_t n = ::recv(c.fd, &first, 1, MSG_PEEK);
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return Handshake::Wait;
        if (n <= 0) return Handshake::Failed;
        if (first != 22) return Handshake::PlainHttp;
        c.sniffed = true;
    }
    ERR_clear_error();
    const int done = SSL_do_handshake(c.tls.get());
    if (done == 1) {
        c.handshaking = false;
        watch(c, false);
        return Handshake::Done;
    }
    switch (SSL_get_error(c.tls.get(), done)) {
    case SSL_ERROR_WANT_READ:
        watch(c, false);
        return Handshake::Wait;
    case SSL_ERROR_WANT_WRITE:
        watch(c, true);
        return Handshake::Wait;
    default:
        ERR_clear_error();
        return Handshake::Failed;
    }
}

ssize_t ConnectionGate::receive(Connection& c, char* buffer, std::size_t size) {
    if (!c.tls) return ::recv(c.fd, buffer, size, 0);
    ERR_clear_error();
    const int n = SSL_read(c.tls.get(), buffer, static_cast<int>(size));
    if (n > 0) return n;
    const int error = SSL_get_error(c.tls.get(), n);
    if (error == SSL_ERROR_WANT_READ || error == SSL_ERROR_WANT_WRITE) {
        errno = EAGAIN;
        return -1;
    }
    ERR_clear_error();
    return 0; // closed, or failed: either way the connection has ended
}

void ConnectionGate::sendNow(Connection& c, std::string_view bytes) {
    sendBytesNow(c.fd, c.tls.get(), bytes);
}

void ConnectionGate::readFrom(Connection& c) {
    if (c.handshaking) {
        switch (advanceHandshake(c)) {
        case Handshake::Wait:
            return;
        case Handshake::Failed:
            close(c.fd);
            return;
        case Handshake::PlainHttp:
            c.tls.reset();
            c.handshaking = false;
            refuse(c, 400, "this port serves HTTPS only: use https://");
            return;
        case Handshake::Done:
            break;
        }
    }
    std::array<char, 16384> buffer;
    bool ended = false; // the client closed its side (or the socket failed)
    for (;;) {
        const ssize_t n = c.draining ? ::recv(c.fd, buffer.data(), buffer.size(), 0)
                                     : receive(c, buffer.data(), buffer.size());
        if (n > 0) {
            if (!c.draining) c.bytes.append(buffer.data(), static_cast<std::size_t>(n));
            if (!c.draining && c.bytes.size() > mLimits.maxHeadBytes + mLimits.maxBodyBytes) break;
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
        ended = true;
        break;
    }
    if (c.draining && !ended) return;
    const Verdict verdict = c.draining ? Verdict::Wait : judge(c);
    // A client may send its request and shut down its sending side; it still reads the answer.
    if (ended && verdict != Verdict::Dispatch) {
        close(c.fd);
        return;
    }
    switch (verdict) {
    case Verdict::Wait:
        return;
    case Verdict::WaitAfterContinue:
        if (!c.continued) {
            sendNow(c, "HTTP/1.1 100 Continue\r\n\r\n");
            c.continued = true;
        }
        return;
    case Verdict::ChunkedBody:
        refuse(c, 411, "a request body needs a Content-Length (chunked transfer is not accepted)");
        return;
    case Verdict::Dispatch:
        dispatch(c);
        return;
    case Verdict::TooLongTarget:
        refuse(c, 414, "request target too long");
        return;
    case Verdict::TooLargeHead:
        refuse(c, 431,
               "request head too large (at most " + std::to_string(mLimits.maxHeaderLines) +
                   " header lines and " + std::to_string(mLimits.maxHeadBytes / 1024) + " KiB)");
        return;
    }
}

ConnectionGate::Verdict ConnectionGate::judge(const Connection& c) const {
    const std::string& bytes = c.bytes;
    const std::size_t lineEnd = bytes.find('\n');
    if ((lineEnd == std::string::npos ? bytes.size() : lineEnd) > mLimits.maxRequestLine)
        return Verdict::TooLongTarget;
    const std::size_t end = headEnd(bytes);
    const std::size_t headSize = end == std::string::npos ? bytes.size() : end;
    const auto lines = static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + headSize, '\n'));
    if (headSize > mLimits.maxHeadBytes || lines > mLimits.maxHeaderLines + 2) return Verdict::TooLargeHead;
    if (end == std::string::npos) return Verdict::Wait;

    // The body: wait for Content-Length bytes when they are few, also behind "Expect: 100-continue" (the
    // gate says 100 itself); chunked bodies are refused here, so no worker waits for their chunks;
    // anything else is the handler's to refuse (a body above the limit, a malformed length, another
    // expectation).
    std::size_t contentLength = 0;
    bool expectContinue = false;
    std::string_view head(bytes.data(), end);
    for (std::size_t pos = lineEnd + 1; pos < end;) {
        const std::size_t next = head.find('\n', pos);
        const std::string_view line = head.substr(pos, (next == std::string::npos ? end : next) - pos);
        pos = next == std::string::npos ? end : next + 1;
        const std::size_t colon = line.find(':');
        if (colon == std::string_view::npos) continue;
        const std::string_view name = trimmed(line.substr(0, colon));
        const std::string_view value = trimmed(line.substr(colon + 1));
        if (equalsIgnoringCase(name, "Transfer-Encoding")) return Verdict::ChunkedBody;
        if (equalsIgnoringCase(name, "Expect")) {
            if (!equalsIgnoringCase(value, "100-continue")) return Verdict::Dispatch;
            expectContinue = true;
        }
        if (equalsIgnoringCase(name, "Content-Length")) {
            const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), contentLength);
            if (ec != std::errc() || ptr != value.data() + value.size() ||
                contentLength > mLimits.maxBodyBytes)
                return Verdict::Dispatch;
        }
    }
    if (bytes.size() >= end + contentLength) return Verdict::Dispatch;
    return expectContinue ? Verdict::WaitAfterContinue : Verdict::Wait;
}

void ConnectionGate::dispatch(Connection& c) {
    ArrivedRequest request;
    request.fd = c.fd;
    request.bytes = std::move(c.bytes);
    // The body is here already: without its Expect line the handler does not say 100 a second time.
    eraseExpectContinue(request.bytes);
    const std::size_t lineEnd = request.bytes.find('\n');
    const std::string_view line(request.bytes.data(), lineEnd);
    const std::size_t space = line.find(' ');
    if (space != std::string_view::npos) {
        request.method = std::string(line.substr(0, space));
        const std::size_t second = line.find(' ', space + 1);
        request.target = std::string(line.substr(
            space + 1, second == std::string_view::npos ? std::string_view::npos : second - space - 1));
    }
    sockaddr_storage addr{};
    socklen_t length = sizeof addr;
    if (::getpeername(c.fd, reinterpret_cast<sockaddr*>(&addr), &length) == 0)
        addressOf(addr, request.peerAddress, request.peerPort);
    length = sizeof addr;
    if (::getsockname(c.fd, reinterpret_cast<sockaddr*>(&addr), &length) == 0)
        addressOf(addr, request.localAddress, request.localPort);

    ::epoll_ctl(mEpoll, EPOLL_CTL_DEL, c.fd, nullptr);
    // A TLS socket stays non-blocking: a readable socket may hold only part of a record, and a blocking
    // SSL_read would then wait past any time limit for the rest.
    setBlocking(c.fd, !c.tls);
    request.tls = std::move(c.tls);
    mConnections.erase(c.fd); // c is gone from here on
    --mWaitingCount;
    mDispatch(std::move(request));
}

void ConnectionGate::refuse(Connection& c, int status, const char* message) {
    refuse(c, status, std::string(message));
}

void ConnectionGate::refuse(Connection& c, int status, const std::string& message) {
    sendNow(c, jsonErrorAnswer(status, message));
    if (c.tls) SSL_shutdown(c.tls.get()); // close_notify; what the client still sends is then dropped
    ::shutdown(c.fd, SHUT_WR);
    c.bytes.clear();
    c.bytes.shrink_to_fit();
    c.draining = true;
    c.accepted = Clock::now() - mLimits.wholeRequest + DRAIN_TIME; // the sweep closes it after DRAIN_TIME
}

void ConnectionGate::sweep(Clock::time_point now) {
    std::vector<int> expired;
    for (const auto& [fd, c] : mConnections) {
        const auto age = now - c.accepted;
        if (age > mLimits.wholeRequest || (c.bytes.empty() && !c.draining && age > mLimits.firstByte))
            expired.push_back(fd);
    }
    for (const int fd : expired)
        close(fd);
}

void ConnectionGate::close(int fd) {
    ::epoll_ctl(mEpoll, EPOLL_CTL_DEL, fd, nullptr);
    ::close(fd);
    if (mConnections.erase(fd)) --mWaitingCount;
}

} // namespace vots::server
