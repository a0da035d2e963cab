// TlsSocketStream: an Asio stream over a TLS session whose handshake the ConnectionGate has already done,
// so that Beast's WebSocket runs over HTTPS connections too (Boost's ssl::stream cannot adopt a session).
#pragma once

#include "connection/TlsContext.h"

#include <boost/asio/async_result.hpp>
#include <boost/asio/buffer.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/beast/core/bind_handler.hpp>
#include <boost/beast/core/error.hpp>
#include <boost/beast/core/role.hpp>

#include <cstddef>
#include <utility>

namespace vots::server {

/// Not thread-safe: used on its io_context's thread only. One read and one write may be in flight at once.
class TlsSocketStream {
public:
    using executor_type = boost::asio::ip::tcp::socket::executor_type;

    /// socket: the connection's (non-blocking) fd, taken over; tls: its session, handshake done.
    TlsSocketStream(boost::asio::ip::tcp::socket socket, TlsSession tls)
        : mSocket(std::move(socket)), mTls(std::move(tls)) {}

    executor_type get_executor() noexcept { return mSocket.get_executor(); }

    template <class Buffers, class Handler> auto async_read_some(const Buffers& buffers, Handler&& handler) {
        return start(Direction::Read, firstNonEmpty<boost::asio::mutable_buffer>(buffers),
                     std::forward<Handler>(handler));
    }
    template <class Buffers, class Handler> auto async_write_some(const Buffers& buffers, Handler&& handler) {
        const boost::asio::const_buffer data = firstNonEmpty<boost::asio::const_buffer>(buffers);
        return start(Direction::Write,
                     boost::asio::mutable_buffer(const_cast<void*>(data.data()), data.size()),
                     std::forward<Handler>(handler));
    }

    /// Sends close_notify (best effort, without waiting), then closes the socket; the waits end.
    void shutdownAndClose();
    /// Closes the socket at once (a timeout, a failed write); the waits end.
    void close();

private:
    enum class Direction { Read, Write };
    enum class Step { Done, WantRead, WantWrite };
    using Completion = void(boost::beast::error_code, std::size_t);

    /// One SSL_read or SSL_write: Done with `transferred` set, or Done with ec set (end or failure), or
    /// the readiness to wait for.
    Step step(Direction direction, boost::asio::mutable_buffer buffer, std::size_t& transferred,
              boost::beast::error_code& ec);

    template <class Buffer, class Buffers> static Buffer firstNonEmpty(const Buffers& buffers) {
        for (auto it = boost::asio::buffer_sequence_begin(buffers);
             it != boost::asio::buffer_sequence_end(buffers); ++it)
            if (Buffer(*it).size() > 0) return Buffer(*it);
        return Buffer();
    }

    template <class Handler>
    auto start(Direction direction, boost::asio::mutable_buffer buffer, Handler&& handler) {
        return boost::asio::async_initiate<Handler, Completion>(
            [this, direction, buffer](auto completion) {
                std::size_t transferred = 0;
                boost::beast::error_code ec;
                const Step next = buffer.size() == 0 ? Step::Done : step(direction, buffer, transferred, ec);
                // Asio's rule: no completion inside the initiating call, so a result already there is posted.
                if (next == Step::Done)
                    return boost::asio::post(
                        mSocket.get_executor(),
                        boost::beast::bind_front_handler(std::move(completion), ec, transferred));
                waitThenRetry(next, direction, buffer, std::move(completion));
            },
            handler);
    }

    /// Waits for the readiness OpenSSL asked for, then repeats the same call (a write must be repeated with
    /// the same bytes); completes from the wait's handler.
    template <class Then>
    void waitThenRetry(Step wanted, Direction direction, boost::asio::mutable_buffer buffer, Then then) {
        mSocket.async_wait(
            wanted == Step::WantRead ? boost::asio::socket_base::wait_read
                                     : boost::asio::socket_base::wait_write,
            [this, direction, buffer, then = std::move(then)](boost::beast::error_code waited) mutable {
                if (waited) return std::move(then)(waited, std::size_t{0});
                std::size_t transferred = 0;
                boost::beast::error_code ec;
                const Step next = step(direction, buffer, transferred, ec);
                if (next == Step::Done) return std::move(then)(ec, transferred);
                waitThenRetry(next, direction, buffer, std::move(then));
            });
    }

    boost::asio::ip::tcp::socket mSocket;
    TlsSession mTls;
};

/// Beast's close of a socket-like layer (its timeouts): the socket closes at once.
inline void beast_close_socket(TlsSocketStream& stream) {
    stream.close();
}

/// Beast's end of a WebSocket after the close frames: close_notify, then the socket closes.
void teardown(boost::beast::role_type, TlsSocketStream& stream, boost::beast::error_code& ec);

template <class Handler>
void async_teardown(boost::beast::role_type, TlsSocketStream& stream, Handler&& handler) {
    stream.shutdownAndClose();
    boost::asio::post(stream.get_executor(), boost::beast::bind_front_handler(std::forward<Handler>(handler),
                                                                              boost::beast::error_code{}));
}

} // namespace vots::server
