// TlsSocketStream: one non-blocking SSL_read or SSL_write at a time, and the end of the connection.
#include "connection/TlsSocketStream.h"

#include <boost/asio/error.hpp>
#include <openssl/err.h>
#include <openssl/ssl.h>

#include <algorithm>
#include <climits>

namespace vots::server {

TlsSocketStream::Step TlsSocketStream::step(Direction direction, boost::asio::mutable_buffer buffer,
                                            std::size_t& transferred, boost::beast::error_code& ec) {
    if (!mSocket.is_open()) {
        ec = boost::asio::error::bad_descriptor;
        return Step::Done;
    }
    const int size = static_cast<int>(std::min<std::size_t>(buffer.size(), INT_MAX));
    ERR_clear_error();
    const int n = direction == Direction::Read ? SSL_read(mTls.get(), buffer.data(), size)
                                               : SSL_write(mTls.get(), buffer.data(), size);
    if (n > 0) {
        transferred = static_cast<std::size_t>(n);
        return Step::Done;
    }
    const int error = SSL_get_error(mTls.get(), n);
    ERR_clear_error();
    switch (error) {
    case SSL_ERROR_WANT_READ:
        return Step::WantRead;
    case SSL_ERROR_WANT_WRITE:
        return Step::WantWrite;
    case SSL_ERROR_ZERO_RETURN: // the client's close_notify
        ec = boost::asio::error::eof;
        return Step::Done;
    default: // a protocol failure, or the connection cut without close_notify
        ec = boost::asio::error::connection_reset;
        return Step::Done;
    }
}

void TlsSocketStream::shutdownAndClose() {
    if (mSocket.is_open()) {
        ERR_clear_error();
        SSL_shutdown(mTls.get());
        ERR_clear_error();
    }
    close();
}

void TlsSocketStream::close() {
    boost::beast::error_code ignored;
    mSocket.shutdown(boost::asio::socket_base::shutdown_both, ignored);
    mSocket.close(ignored);
}

void teardown(boost::beast::role_type, TlsSocketStream& stream, boost::beast::error_code& ec) {
    stream.shutdownAndClose();
    ec = {};
}

} // namespace vots::server
