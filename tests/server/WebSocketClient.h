// A blocking WebSocket client for the server tests (Boost.Beast), with a receive timeout so that a test
// that waits for a message the server never sends fails instead of hanging.
#pragma once

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>

#include <sys/socket.h>
#include <sys/time.h>

#include <map>
#include <optional>
#include <string>

namespace vots::test {

class WebSocketClient {
public:
    struct Message {
        bool text = false;
        std::string bytes;
    };

    /// Connects from `source` (a loopback address: 127.0.0.2 is another client) and sends the upgrade;
    /// handshakeOk() says whether the server took it, response() what it said.
    WebSocketClient(int port, const std::string& target,
                    const std::map<std::string, std::string>& headers = {}, const std::string& host = "",
                    const std::string& source = "127.0.0.1")
        : mWs(mIo) {
        namespace net = boost::asio;
        mWs.next_layer().open(net::ip::tcp::v4());
        mWs.next_layer().bind({net::ip::make_address(source), 0});
        mWs.next_layer().connect({net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)});
        const timeval timeout{60, 0}; // no test waits this long for a message that comes
        ::setsockopt(mWs.next_layer().native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
        mWs.set_option(boost::beast::websocket::stream_base::decorator(
            [headers](boost::beast::websocket::request_type& req) {
                for (const auto& [name, value] : headers)
                    req.set(name, value);
            }));
        mWs.read_message_max(64 * 1024 * 1024);
        mWs.handshake(mResponse, host.empty() ? "127.0.0.1:" + std::to_string(port) : host, target, mError);
    }

    bool handshakeOk() const { return !mError; }
    std::string handshakeError() const { return mError.message(); }
    const boost::beast::websocket::response_type& response() const { return mResponse; }

    bool sendText(const std::string& text) {
        boost::beast::error_code ec;
        mWs.text(true);
        mWs.write(boost::asio::buffer(text), ec);
        return !ec;
    }
    bool sendBinary(const std::string& bytes) {
        boost::beast::error_code ec;
        mWs.binary(true);
        mWs.write(boost::asio::buffer(bytes), ec);
        return !ec;
    }
    /// The next message, or none once the socket is closed (closeCode() then says how) or timed out.
    std::optional<Message> read() {
        boost::beast::flat_buffer buffer;
        boost::beast::error_code ec;
        mWs.read(buffer, ec);
        if (ec) return std::nullopt;
        return Message{mWs.got_text(), boost::beast::buffers_to_string(buffer.data())};
    }
    /// The code of the server's close frame (0 when none came).
    int closeCode() const { return static_cast<int>(mWs.reason().code); }

private:
    boost::asio::io_context mIo;
    boost::beast::websocket::stream<boost::asio::ip::tcp::socket> mWs;
    boost::beast::websocket::response_type mResponse;
    boost::beast::error_code mError;
};

} // namespace vots::test
