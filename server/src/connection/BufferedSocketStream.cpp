// BufferedSocketStream: reads the gate's bytes first, then the socket; writes go straight to the socket.
#include "connection/BufferedSocketStream.h"

#include <openssl/err.h>
#include <openssl/ssl.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>

namespace vots::server {

BufferedSocketStream::BufferedSocketStream(const ArrivedRequest& request, std::chrono::milliseconds timeout)
    : mRequest(request), mTimeout(timeout) {}

bool BufferedSocketStream::waitFor(short events) const {
    pollfd p{mRequest.fd, events, 0};
    for (;;) {
        const int n = ::poll(&p, 1, static_cast<int>(mTimeout.count()));
        if (n < 0 && errno == EINTR) continue;
        return n > 0 && (p.revents & events) != 0;
    }
}

bool BufferedSocketStream::is_readable() const {
    return mOffset < mRequest.bytes.size() || (mRequest.tls && SSL_pending(mRequest.tls.get()) > 0) ||
           waitFor(POLLIN);
}

template <typename Transfer> ssize_t BufferedSocketStream::throughTls(Transfer transfer) {
    for (;;) {
        ERR_clear_error();
        const int n = transfer();
        if (n > 0) return n;
        switch (SSL_get_error(mRequest.tls.get(), n)) {
        case SSL_ERROR_WANT_READ:
            if (!waitFor(POLLIN)) return -1;
            continue;
        case SSL_ERROR_WANT_WRITE:
            if (!waitFor(POLLOUT)) return -1;
            continue;
        case SSL_ERROR_ZERO_RETURN:
            return 0;
        default:
            ERR_clear_error();
            return -1;
        }
    }
}

void BufferedSocketStream::shutdownTls() {
    if (!mRequest.tls) return;
    ERR_clear_error();
    SSL_shutdown(mRequest.tls.get());
    ERR_clear_error();
}

bool BufferedSocketStream::is_writable() const {
    return waitFor(POLLOUT);
}

ssize_t BufferedSocketStream::read(char* ptr, std::size_t size) {
    if (mOffset < mRequest.bytes.size()) {
        const std::size_t n = std::min(size, mRequest.bytes.size() - mOffset);
        std::memcpy(ptr, mRequest.bytes.data() + mOffset, n);
        mOffset += n;
        return static_cast<ssize_t>(n);
    }
    const int most = static_cast<int>(std::min<std::size_t>(size, INT_MAX));
    if (mRequest.tls) return throughTls([&] { return SSL_read(mRequest.tls.get(), ptr, most); });
    if (!waitFor(POLLIN)) return -1;
    for (;;) {
        const ssize_t n = ::recv(mRequest.fd, ptr, size, 0);
        if (n < 0 && errno == EINTR) continue;
        return n;
    }
}

ssize_t BufferedSocketStream::write(const char* ptr, std::size_t size) {
    const int most = static_cast<int>(std::min<std::size_t>(size, INT_MAX));
    if (mRequest.tls) return throughTls([&] { return SSL_write(mRequest.tls.get(), ptr, most); });
    if (!waitFor(POLLOUT)) return -1;
    for (;;) {
        const ssize_t n = ::send(mRequest.fd, ptr, size, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        return n;
    }
}

void BufferedSocketStream::get_remote_ip_and_port(std::string& ip, int& port) const {
    ip = mRequest.peerAddress;
    port = mRequest.peerPort;
}

void BufferedSocketStream::get_local_ip_and_port(std::string& ip, int& port) const {
    ip = mRequest.localAddress;
    port = mRequest.localPort;
}

} // namespace vots::server
