// `vots serve --tls-cert/--tls-key`: HTTPS with a test CA made here by the openssl command, plain HTTP
// refused on that port, the viewer socket over wss://, clear start-up errors, SIGHUP reload, handshakes
// that hold no worker; and the refusal to serve in clear beyond loopback.
#include "ServeProcess.h"

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <netinet/in.h>
#include <openssl/ssl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <optional>

namespace vots::test {
namespace {

/// A CA and a server certificate for 127.0.0.1 signed by it, made by the openssl command in `dir`:
/// NAME-ca.pem, NAME.pem and NAME.key.
void makeCertificate(const TempDir& dir, const std::string& name) {
    const std::string d = dir.path().string() + "/";
    dir.write("san.ext", "subjectAltName=IP:127.0.0.1\n");
    const std::string ec = " -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes";
    const std::string script = "set -e; cd '" + d + "'; openssl req -x509" + ec + " -keyout " + name +
                               "-ca.key -out " + name + "-ca.pem -days 2 -subj /CN=" + name +
                               "-ca; openssl req" + ec + " -keyout " + name + ".key -out " + name +
                               ".csr -subj /CN=127.0.0.1; openssl x509 -req -in " + name + ".csr -CA " +
                               name + "-ca.pem -CAkey " + name + "-ca.key -CAcreateserial -out " + name +
                               ".pem -days 2 -extfile san.ext 2>/dev/null";
    ASSERT_EQ(std::system(script.c_str()), 0) << script;
}

std::unique_ptr<httplib::SSLClient> httpsClient(int port, const std::string& caFile) {
    auto c = std::make_unique<httplib::SSLClient>("127.0.0.1", port);
    c->set_ca_cert_path(caFile.c_str());
    c->enable_server_certificate_verification(true);
    c->set_read_timeout(30);
    return c;
}

int connectTo(int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

/// A TLS client connection by OpenSSL itself, trusting only `caFile`, for a request sent in two parts.
class TlsConnection {
public:
    TlsConnection(int port, const std::string& caFile)
        : mContext(SSL_CTX_new(TLS_client_method()), SSL_CTX_free), mFd(connectTo(port)) {
        SSL_CTX_load_verify_locations(mContext.get(), caFile.c_str(), nullptr);
        SSL_CTX_set_verify(mContext.get(), SSL_VERIFY_PEER, nullptr);
        mSsl.reset(SSL_new(mContext.get()));
        SSL_set_fd(mSsl.get(), mFd);
        mConnected = mFd >= 0 && SSL_connect(mSsl.get()) == 1;
    }
    ~TlsConnection() { ::close(mFd); }
    bool connected() const { return mConnected; }
    bool send(const std::string& bytes) {
        return SSL_write(mSsl.get(), bytes.data(), static_cast<int>(bytes.size())) ==
               static_cast<int>(bytes.size());
    }
    std::string readAll() {
        std::string all;
        char buffer[4096];
        for (int n; (n = SSL_read(mSsl.get(), buffer, sizeof buffer)) > 0;)
            all.append(buffer, static_cast<std::size_t>(n));
        return all;
    }

private:
    std::unique_ptr<SSL_CTX, decltype(&SSL_CTX_free)> mContext;
    std::unique_ptr<SSL, decltype(&SSL_free)> mSsl{nullptr, SSL_free};
    int mFd = -1;
    bool mConnected = false;
};

/// The viewer socket over wss://, trusting only `caFile` (checked for 127.0.0.1); blocking, with a time
/// limit on every read.
class SecureWebSocket {
public:
    SecureWebSocket(int port, const std::string& caFile)
        : mContext(boost::asio::ssl::context::tls_client), mWs(mIo, mContext) {
        namespace net = boost::asio;
        boost::beast::error_code ec;
        mContext.load_verify_file(caFile, ec);
        auto& tls = mWs.next_layer();
        tls.set_verify_mode(net::ssl::verify_peer);
        X509_VERIFY_PARAM_set1_ip_asc(SSL_get0_param(tls.native_handle()), "127.0.0.1");
        boost::beast::get_lowest_layer(mWs).connect(
            {net::ip::make_address("127.0.0.1"), static_cast<unsigned short>(port)});
        const timeval timeout{60, 0};
        ::setsockopt(boost::beast::get_lowest_layer(mWs).native_handle(), SOL_SOCKET, SO_RCVTIMEO, &timeout,
                     sizeof timeout);
        tls.handshake(net::ssl::stream_base::client, mError);
        if (!mError) mWs.handshake(mResponse, "127.0.0.1:" + std::to_string(port), "/api/stream", mError);
        mOpen = !mError;
    }

    bool open() const { return mOpen; }
    std::string error() const { return mError.message(); }
    bool send(const std::string& text) {
        mWs.text(true);
        mWs.write(boost::asio::buffer(text), mError);
        return !mError;
    }
    std::optional<std::string> read() {
        boost::beast::flat_buffer buffer;
        mWs.read(buffer, mError);
        if (mError) return std::nullopt;
        return boost::beast::buffers_to_string(buffer.data());
    }
    int closeCode() const { return static_cast<int>(mWs.reason().code); }

private:
    boost::asio::io_context mIo;
    boost::asio::ssl::context mContext;
    boost::beast::websocket::stream<boost::beast::ssl_stream<boost::asio::ip::tcp::socket>> mWs;
    boost::beast::websocket::response_type mResponse;
    boost::beast::error_code mError;
    bool mOpen = false;
};

class ServeCommandTls : public ::testing::Test {
protected:
    void SetUp() override { makeCertificate(world.dir(), "first"); }
    std::vector<std::string> tlsArgs() const {
        return {"--tls-cert", world.dir().file("first.pem"), "--tls-key", world.dir().file("first.key")};
    }
    std::string ca() const { return world.dir().file("first-ca.pem"); }

    ServerWorld world;
};

TEST_F(ServeCommandTls, AnswersOverHttpsWithHstsAndRefusesPlainHttp) {
    ServeProcess serve(world, tlsArgs());
    ASSERT_GT(serve.port(), 0) << serve.output();
    EXPECT_NE(serve.output().find("listening on https://"), std::string::npos) << serve.output();
    const auto res = httpsClient(serve.port(), ca())->Get("/api/datasets");
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->status, 200);
    EXPECT_NE(res->body.find("blobs"), std::string::npos) << res->body;
    EXPECT_EQ(res->get_header_value("Strict-Transport-Security"), "max-age=31536000");
    const auto page = httpsClient(serve.port(), ca())->Get("/");
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 200);

    const auto plain = serve.client()->Get("/api/datasets");
    ASSERT_TRUE(plain) << httplib::to_string(plain.error());
    EXPECT_EQ(plain->status, 400);
    EXPECT_NE(plain->body.find("HTTPS only"), std::string::npos) << plain->body;
    EXPECT_EQ(plain->body.find("blobs"), std::string::npos);

    // A client that does not trust the test CA does not get through.
    auto untrusting = std::make_unique<httplib::SSLClient>("127.0.0.1", serve.port());
    untrusting->enable_server_certificate_verification(true);
    untrusting->set_ca_cert_path(world.dir().file("san.ext").c_str());
    EXPECT_FALSE(untrusting->Get("/api/datasets"));
    EXPECT_EQ(serve.stop(), 0);
}

TEST_F(ServeCommandTls, TheViewerSocketServesFramesOverWss) {
    ServeProcess serve(world, tlsArgs());
    ASSERT_GT(serve.port(), 0) << serve.output();
    SecureWebSocket socket(serve.port(), ca());
    ASSERT_TRUE(socket.open()) << socket.error();
    const std::string view =
        nlohmann::json{{"type", "view"},
                       {"seq", 1},
                       {"still", false},
                       {"params", {{"dataset", BLOBS}, {"cam", "az=30"}, {"size", "96x64"}, {"mode", "mip"}}}}
            .dump();
    ASSERT_TRUE(socket.send(view)) << socket.error();
    const auto header = socket.read();
    ASSERT_TRUE(header) << socket.error();
    const auto json = nlohmann::json::parse(*header);
    EXPECT_EQ(json["type"], "frame") << *header;
    EXPECT_EQ(json["seq"], 1);
    const auto image = socket.read();
    ASSERT_TRUE(image) << socket.error();
    ASSERT_GT(image->size(), 2u);
    EXPECT_EQ(image->substr(0, 2), "\xFF\xD8") << "a JPEG draft";

    // The same bounds as in clear: a message above 8 KiB closes the socket with 1009.
    ASSERT_TRUE(socket.send(std::string(9000, 'x')));
    while (socket.read()) {
    }
    EXPECT_EQ(socket.closeCode(), 1009) << socket.error();

    // And the same guard, its refusal answered through TLS: another page's Origin is refused.
    TlsConnection foreign(serve.port(), ca());
    ASSERT_TRUE(foreign.connected());
    ASSERT_TRUE(foreign.send("GET /api/stream HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(serve.port()) +
                             "\r\nOrigin: https://elsewhere.example\r\nUpgrade: websocket\r\n"
                             "Connection: Upgrade\r\nSec-WebSocket-Version: 13\r\n"
                             "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n\r\n"));
    const std::string refusal = foreign.readAll();
    EXPECT_EQ(refusal.rfind("HTTP/1.1 403", 0), 0u) << refusal.substr(0, 200);
    EXPECT_NE(refusal.find("other origins"), std::string::npos) << refusal;
    EXPECT_EQ(serve.stop(), 0);
}

TEST_F(ServeCommandTls, IdleAndHalfDoneHandshakesHoldNoWorker) {
    ServeProcess serve(world, tlsArgs());
    ASSERT_GT(serve.port(), 0) << serve.output();
    // More than the server's 12 workers: silent connections, and handshakes begun and left (the first
    // bytes of a ClientHello record).
    std::vector<int> waiting;
    for (int i = 0; i < 40; ++i) {
        const int fd = connectTo(serve.port());
        ASSERT_GE(fd, 0);
        if (i % 2) {
            const unsigned char start[] = {0x16, 0x03, 0x01, 0x02};
            ASSERT_EQ(::send(fd, start, sizeof start, MSG_NOSIGNAL), static_cast<ssize_t>(sizeof start));
        }
        waiting.push_back(fd);
    }
    const auto res = httpsClient(serve.port(), ca())->Get("/api/datasets");
    ASSERT_TRUE(res) << httplib::to_string(res.error());
    EXPECT_EQ(res->status, 200);
    // Answered while every one of them is still held open: nothing waited for them to time out.
    for (const int fd : waiting) {
        char byte = 0;
        EXPECT_EQ(::recv(fd, &byte, 1, MSG_DONTWAIT), -1);
        EXPECT_TRUE(errno == EAGAIN || errno == EWOULDBLOCK);
        ::close(fd);
    }
    EXPECT_EQ(serve.stop(), 0);
}

TEST_F(ServeCommandTls, SighupReadsANewCertificateAndABadOneKeepsTheOld) {
    makeCertificate(world.dir(), "second");
    const std::string cert = world.dir().file("live.pem"), key = world.dir().file("live.key");
    std::filesystem::copy_file(world.dir().file("first.pem"), cert);
    std::filesystem::copy_file(world.dir().file("first.key"), key);
    ServeProcess serve(world, {"--tls-cert", cert, "--tls-key", key});
    ASSERT_GT(serve.port(), 0) << serve.output();
    // A connection made before the reloads, its request begun, is answered after them.
    TlsConnection early(serve.port(), ca());
    ASSERT_TRUE(early.connected());
    ASSERT_TRUE(early.send("GET /api/datasets HTTP/1.1\r\n"));

    const auto reloads = [&serve] {
        std::size_t n = 0;
        const std::string out = serve.output();
        for (const char* line : {"read again", "stays in force"})
            for (auto at = out.find(line); at != std::string::npos; at = out.find(line, at + 1))
                ++n;
        return n;
    };
    const auto waitForReloads = [&](std::size_t n) {
        for (int i = 0; i < 200 && reloads() < n; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        return reloads();
    };
    // A broken pair is refused and the certificate in force stays.
    world.dir().write("live.key", "not a key\n");
    serve.signal(SIGHUP);
    ASSERT_EQ(waitForReloads(1), 1u) << serve.output();
    EXPECT_NE(serve.output().find("previous certificate stays in force"), std::string::npos)
        << serve.output();
    ASSERT_TRUE(httpsClient(serve.port(), ca())->Get("/api/datasets"));

    std::filesystem::copy_file(world.dir().file("second.pem"), cert,
                               std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(world.dir().file("second.key"), key,
                               std::filesystem::copy_options::overwrite_existing);
    serve.signal(SIGHUP);
    ASSERT_EQ(waitForReloads(2), 2u) << serve.output();
    const auto fresh = httpsClient(serve.port(), world.dir().file("second-ca.pem"))->Get("/api/datasets");
    ASSERT_TRUE(fresh) << httplib::to_string(fresh.error());
    EXPECT_EQ(fresh->status, 200);
    EXPECT_FALSE(httpsClient(serve.port(), ca())->Get("/api/datasets"));
    ASSERT_TRUE(early.send("Host: 127.0.0.1\r\n\r\n"));
    const std::string answer = early.readAll();
    EXPECT_EQ(answer.rfind("HTTP/1.1 200", 0), 0u) << answer.substr(0, 200);
    EXPECT_NE(answer.find("blobs"), std::string::npos);
    EXPECT_EQ(serve.stop(), 0);
}

TEST_F(ServeCommandTls, ABadCertificateOrKeyIsAClearStartUpError) {
    ServeProcess missing(
        world, {"--tls-cert", world.dir().file("nope.pem"), "--tls-key", world.dir().file("first.key")});
    EXPECT_LT(missing.port(), 0);
    EXPECT_NE(missing.stop(), 0);
    EXPECT_NE(missing.err().find("nope.pem"), std::string::npos) << missing.err();

    world.dir().write("garbage.pem", "not a certificate\n");
    ServeProcess garbage(
        world, {"--tls-cert", world.dir().file("garbage.pem"), "--tls-key", world.dir().file("first.key")});
    EXPECT_LT(garbage.port(), 0);
    EXPECT_EQ(garbage.stop(), 2);
    EXPECT_NE(garbage.err().find("cannot read the TLS certificate"), std::string::npos) << garbage.err();

    makeCertificate(world.dir(), "other");
    ServeProcess mismatched(
        world, {"--tls-cert", world.dir().file("first.pem"), "--tls-key", world.dir().file("other.key")});
    EXPECT_LT(mismatched.port(), 0);
    EXPECT_EQ(mismatched.stop(), 2);
    EXPECT_NE(mismatched.err().find("does not belong to the certificate"), std::string::npos)
        << mismatched.err();

    ServeProcess lonely(world, {"--tls-cert", world.dir().file("first.pem")});
    EXPECT_LT(lonely.port(), 0);
    EXPECT_NE(lonely.stop(), 0);
    EXPECT_NE(lonely.err().find("--tls-key"), std::string::npos) << lonely.err();
}

TEST(ServeCommandCleartext, BeyondLoopbackPlainHttpNeedsToBeAskedFor) {
    ServerWorld world;
    ServeProcess refused(world, {"--host", "0.0.0.0"});
    EXPECT_LT(refused.port(), 0);
    EXPECT_EQ(refused.stop(), 2);
    EXPECT_NE(refused.err().find("needs HTTPS"), std::string::npos) << refused.err();

    ServeProcess insecure(world, {"--host", "0.0.0.0", "--insecure-http"});
    EXPECT_GT(insecure.port(), 0) << insecure.output();
    EXPECT_EQ(insecure.stop(), 0);
    EXPECT_NE(insecure.err().find("warning: --insecure-http"), std::string::npos) << insecure.err();

    ServeProcess proxied(world, {"--host", "0.0.0.0", "--behind-proxy", "127.0.0.1"});
    EXPECT_GT(proxied.port(), 0) << proxied.output();
    EXPECT_EQ(proxied.stop(), 0);
    EXPECT_EQ(proxied.err().find("warning"), std::string::npos) << proxied.err();
}

} // namespace
} // namespace vots::test
