// GET /api/stream over loopback: drafts are JPEG at the budget's size, the still is /render's PNG byte for
// byte, the latest view wins under acknowledgement pacing, the upgrade passes the guard, and broken
// messages close the socket with their code.
#include "RawClient.h"
#include "ServerFixture.h"
#include "WebSocketClient.h"

#include "vots/render/Jpeg.h"

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

namespace vots::test {
namespace {

constexpr const char* TOKEN = "f00dfeedf00dfeedf00dfeed";
const std::string CAM = "az=30,el=20";

std::string viewMessage(std::uint64_t seq, bool still, const std::string& cam = CAM,
                        const std::string& size = "96x64") {
    return nlohmann::json{{"type", "view"},
                          {"seq", seq},
                          {"still", still},
                          {"params", {{"dataset", BLOBS}, {"cam", cam}, {"size", size}, {"mode", "mip"}}}}
        .dump();
}

std::string ackMessage(std::uint64_t frame) {
    return nlohmann::json{{"type", "ack"}, {"frame", frame}}.dump();
}

struct Frame {
    nlohmann::json header;
    std::string bytes;
};

/// The next frame (header, then image); a test failure when an error or a close comes instead.
Frame readFrame(WebSocketClient& socket) {
    const auto header = socket.read();
    if (!header || !header->text) {
        ADD_FAILURE() << "no frame header; close code " << socket.closeCode();
        return {};
    }
    Frame frame{nlohmann::json::parse(header->bytes), {}};
    if (frame.header["type"] != "frame") {
        ADD_FAILURE() << "not a frame: " << header->bytes;
        return frame;
    }
    const auto image = socket.read();
    if (!image || image->text) {
        ADD_FAILURE() << "no image after the header";
        return frame;
    }
    frame.bytes = image->bytes;
    return frame;
}

/// Reads until the server closes; its close code.
int closeCodeAfter(WebSocketClient& socket) {
    for (int i = 0; i < 100 && socket.read(); ++i) {
    }
    return socket.closeCode();
}

class ServerViewerStream : public SharedServerTest {};

TEST_F(ServerViewerStream, DraftsAreJpegAndTheStillIsRenderSPng) {
    WebSocketClient socket(sServer->port(), "/api/stream");
    ASSERT_TRUE(socket.handshakeOk());
    ASSERT_TRUE(socket.sendText(viewMessage(1, false)));
    const Frame draft = readFrame(socket);
    EXPECT_EQ(draft.header["seq"], 1);
    EXPECT_EQ(draft.header["frame"], 1);
    EXPECT_EQ(draft.header["still"], false);
    EXPECT_EQ(draft.header["format"], "image/jpeg");
    const render::RgbaImage decoded = render::decodeJpeg({draft.bytes.begin(), draft.bytes.end()});
    EXPECT_EQ(decoded.width, draft.header["width"].get<int>());
    EXPECT_EQ(decoded.height, draft.header["height"].get<int>());
    EXPECT_LE(decoded.width, 96);
    EXPECT_GE(decoded.width, 24);
    // The same aspect as the full frame, within a pixel of rounding.
    EXPECT_NEAR(decoded.width * 64.0 / 96.0, decoded.height, 1.0);

    ASSERT_TRUE(socket.sendText(ackMessage(1)));
    ASSERT_TRUE(socket.sendText(viewMessage(2, true)));
    const Frame still = readFrame(socket);
    EXPECT_EQ(still.header["seq"], 2);
    EXPECT_EQ(still.header["format"], "image/png");
    EXPECT_EQ(still.header["width"], 96);
    EXPECT_EQ(still.header["height"], 64);
    const auto png = client()->Get(
        ("/render?dataset=" + std::string(BLOBS) + "&cam=" + CAM + "&size=96x64&mode=mip").c_str());
    ASSERT_TRUE(png);
    ASSERT_EQ(png->status, 200) << png->body;
    EXPECT_TRUE(still.bytes == png->body) << "the still differs from /render's PNG";
}

TEST_F(ServerViewerStream, TheLatestViewWinsAndFramesWaitForAcknowledgements) {
    WebSocketClient socket(sServer->port(), "/api/stream");
    ASSERT_TRUE(socket.handshakeOk());
    ASSERT_TRUE(socket.sendText(viewMessage(1, false, "az=1")));
    EXPECT_EQ(readFrame(socket).header["frame"], 1);
    ASSERT_TRUE(socket.sendText(viewMessage(2, false, "az=2")));
    EXPECT_EQ(readFrame(socket).header["frame"], 2);
    // Two frames unacknowledged: these views wait, each replacing the one before.
    for (std::uint64_t seq = 3; seq <= 20; ++seq)
        ASSERT_TRUE(socket.sendText(viewMessage(seq, false, "az=" + std::to_string(seq))));
    ASSERT_TRUE(socket.sendText(ackMessage(2)));
    const Frame third = readFrame(socket);
    EXPECT_EQ(third.header["frame"], 3);
    EXPECT_EQ(third.header["seq"], 20) << "an older view was drawn: " << third.header.dump();
    // Acknowledging a frame that was never sent is a broken page.
    ASSERT_TRUE(socket.sendText(ackMessage(99)));
    EXPECT_EQ(closeCodeAfter(socket), 1008);
}

TEST_F(ServerViewerStream, BadParametersAreAnsweredAndTheSocketStays) {
    WebSocketClient socket(sServer->port(), "/api/stream");
    ASSERT_TRUE(socket.handshakeOk());
    ASSERT_TRUE(socket.sendText(viewMessage(1, false, "az=30", "0x0")));
    const auto error = socket.read();
    ASSERT_TRUE(error && error->text);
    const auto json = nlohmann::json::parse(error->bytes);
    EXPECT_EQ(json["type"], "error");
    EXPECT_EQ(json["seq"], 1);
    EXPECT_EQ(json["status"], 400);
    ASSERT_TRUE(socket.sendText(nlohmann::json{
        {"type", "view"}, {"seq", 2}, {"params", {{"dataset", "no_such_dataset"}, {"size", "8x8"}}}}
                                    .dump()));
    const auto missing = socket.read();
    ASSERT_TRUE(missing && missing->text);
    EXPECT_EQ(nlohmann::json::parse(missing->bytes)["status"], 404);
    ASSERT_TRUE(socket.sendText(viewMessage(3, false)));
    EXPECT_EQ(readFrame(socket).header["seq"], 3);
}

TEST_F(ServerViewerStream, BrokenMessagesCloseTheSocketWithTheirCode) {
    const auto closedWith = [](const std::function<void(WebSocketClient&)>& send) {
        WebSocketClient socket(sServer->port(), "/api/stream");
        if (!socket.handshakeOk()) return -1;
        send(socket);
        return closeCodeAfter(socket);
    };
    EXPECT_EQ(closedWith([](WebSocketClient& s) { s.sendText("{not json"); }), 1007);
    EXPECT_EQ(closedWith([](WebSocketClient& s) { s.sendText(R"({"type":"dance"})"); }), 1008);
    EXPECT_EQ(closedWith([](WebSocketClient& s) { s.sendBinary("\x01\x02"); }), 1003);
    EXPECT_EQ(closedWith([](WebSocketClient& s) { s.sendText(std::string(9000, ' ')); }), 1009);
    EXPECT_EQ(closedWith([](WebSocketClient& s) { s.sendText(std::string("\"\xff\xfe\"")); }), 1007);
    EXPECT_EQ(closedWith([](WebSocketClient& s) {
                  for (int i = 0; i < 400 && s.sendText(ackMessage(0)); ++i) {
                  }
              }),
              1008);
    // The server still serves after all of them.
    WebSocketClient socket(sServer->port(), "/api/stream");
    ASSERT_TRUE(socket.handshakeOk());
    ASSERT_TRUE(socket.sendText(viewMessage(1, false)));
    EXPECT_EQ(readFrame(socket).header["frame"], 1);
}

/// Pages that acknowledge every frame at once and always have a new view (each its own cameras, never
/// drawn before): they keep the render thread busy for as long as they run. With `stills` their views are
/// stills (full size, no draft budget), so each page always has a frame waiting for the render thread.
class BusyPages {
public:
    BusyPages(int port, int pages, const std::string& source, bool stills = false) : mStills(stills) {
        for (int page = 0; page < pages; ++page) {
            mSockets.push_back(std::make_unique<WebSocketClient>(
                port, "/api/stream", std::map<std::string, std::string>{}, "", source));
            if (!mSockets.back()->handshakeOk()) {
                ADD_FAILURE() << "busy page " << page << " from " << source << " refused";
                continue;
            }
            mThreads.emplace_back([this, page, &socket = *mSockets.back()] { drag(socket, page); });
        }
        while (mFrames < 3 * pages)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    ~BusyPages() {
        mStop = true;
        for (std::thread& thread : mThreads)
            thread.join();
    }
    int frames() const { return mFrames; }

private:
    void drag(WebSocketClient& socket, int page) {
        const auto cam = [page](std::uint64_t seq) {
            return "az=" + std::to_string(page * 50) + "." + std::to_string(seq) + ",el=7";
        };
        const std::string size = mStills ? "320x240" : "128x96";
        std::uint64_t seq = 1;
        socket.sendText(viewMessage(seq, mStills, cam(seq), size));
        while (!mStop) {
            const Frame frame = readFrame(socket);
            if (frame.bytes.empty()) return;
            ++mFrames;
            ++seq;
            socket.sendText(ackMessage(frame.header["frame"].get<std::uint64_t>()));
            socket.sendText(viewMessage(seq, mStills, cam(seq), size));
        }
    }

    const bool mStills;
    std::vector<std::unique_ptr<WebSocketClient>> mSockets;
    std::vector<std::thread> mThreads;
    std::atomic<int> mFrames{0};
    std::atomic<bool> mStop{false};
};

/// How many frames the busy pages get while a page from `source` waits for its one view's frame.
int busyFramesWhileAnotherWaits(int port, const BusyPages& busy, const std::string& source) {
    WebSocketClient other(port, "/api/stream", {}, "", source);
    EXPECT_TRUE(other.handshakeOk());
    const int before = busy.frames();
    EXPECT_TRUE(other.sendText(viewMessage(1, false, "az=77")));
    EXPECT_EQ(readFrame(other).header["seq"], 1);
    return busy.frames() - before;
}

TEST_F(ServerViewerStream, ABusyViewerDoesNotHoldBackAnother) {
    const BusyPages busy(sServer->port(), 1, "127.0.0.1");
    // Its frame comes after at most the busy page's frame being drawn and the one after.
    const int meanwhile = busyFramesWhileAnotherWaits(sServer->port(), busy, "127.0.0.1");
    EXPECT_LE(meanwhile, 3) << "the busy page got " << meanwhile << " frames while the other waited for one";
}

TEST_F(ServerViewerStream, ManyViewersBehindOneAddressDoNotHoldBackAnotherAddress) {
    // Eight pages behind one address (eight views in one browser, or the users behind one proxy) keep
    // the render thread busy: another address is served among them, not starved (the order of turns is
    // OwnerTurns's test; here the encoding and sending of their frames share the cores too).
    constexpr int PAGES = 8;
    const BusyPages busy(sServer->port(), PAGES, "127.0.0.2", true);
    const int meanwhile = busyFramesWhileAnotherWaits(sServer->port(), busy, "127.0.0.3");
    EXPECT_LE(meanwhile, 2 * PAGES) << "eight pages of one address got " << meanwhile
                                    << " frames while another address waited for one";
}

TEST_F(ServerViewerStream, EightViewersAndEightRenderClientsBehindOneAddressAreAllServed) {
    constexpr int PAGES = 8;
    std::vector<std::unique_ptr<WebSocketClient>> pages;
    for (int page = 0; page < PAGES; ++page) {
        pages.push_back(std::make_unique<WebSocketClient>(
            sServer->port(), "/api/stream", std::map<std::string, std::string>{}, "", "127.0.0.4"));
        ASSERT_TRUE(pages.back()->handshakeOk()) << "page " << page;
    }
    // The /render clients ask at the same time as the pages: more than the 4 renders one address may
    // have in progress, so some wait their turn.
    std::vector<int> renderStatus(PAGES, 0);
    std::vector<std::thread> renders;
    for (int i = 0; i < PAGES; ++i)
        renders.emplace_back([&, i] {
            const std::string target = "/render?dataset=" + std::string(BLOBS) +
                                       "&cam=az=" + std::to_string(200 + i) + "&size=256x192&mode=mip";
            renderStatus[i] =
                exchangeFrom("127.0.0.4", sServer->port(), requestText("GET", target, sServer->port()))
                    .status;
        });
    for (int page = 0; page < PAGES; ++page)
        ASSERT_TRUE(pages[page]->sendText(viewMessage(1, false, "az=" + std::to_string(100 + page))));
    for (int page = 0; page < PAGES; ++page) {
        EXPECT_EQ(readFrame(*pages[page]).header["seq"], 1) << "page " << page;
        ASSERT_TRUE(pages[page]->sendText(ackMessage(1)));
        ASSERT_TRUE(pages[page]->sendText(viewMessage(2, true, "az=" + std::to_string(100 + page))));
    }
    for (int page = 0; page < PAGES; ++page)
        EXPECT_EQ(readFrame(*pages[page]).header["still"], true) << "page " << page;
    for (std::thread& render : renders)
        render.join();
    for (int i = 0; i < PAGES; ++i)
        EXPECT_EQ(renderStatus[i], 200) << "/render client " << i;
}

TEST_F(ServerViewerStream, OneAddressOpensAtMost32Sockets) {
    std::vector<std::unique_ptr<WebSocketClient>> open;
    for (int i = 0; i < 32; ++i) {
        open.push_back(std::make_unique<WebSocketClient>(sServer->port(), "/api/stream"));
        ASSERT_TRUE(open.back()->handshakeOk()) << "socket " << i;
    }
    EXPECT_GE(bodyJson(client()->Get("/api/stats"))["connections"]["viewerSockets"].get<int>(), 32);
    const auto res = client()->Get("/api/stream", {{"Upgrade", "websocket"},
                                                   {"Connection", "Upgrade"},
                                                   {"Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="},
                                                   {"Sec-WebSocket-Version", "13"}});
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 429) << res->body;
    open.clear(); // closed without a close frame, as a tab that is killed
    // The server notices the closes on its own thread: a socket opens again soon after.
    bool reopened = false;
    for (int i = 0; i < 100 && !reopened; ++i) {
        WebSocketClient again(sServer->port(), "/api/stream");
        reopened = again.handshakeOk();
        if (!reopened) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    EXPECT_TRUE(reopened);
}

TEST(ServerViewerStreamGuard, TheUpgradePassesHostOriginAndToken) {
    ServerWorld world;
    server::ServerOptions options = world.quietOptions();
    options.accessTokens = {{"operator", server::Role::Operator, TOKEN}};
    LoopbackServer server(options);
    const int port = server.port();
    const std::string own = "http://127.0.0.1:" + std::to_string(port);
    const std::string withToken = std::string("/api/stream?token=") + TOKEN;
    // Beast's client keeps no refused answer (1.74), so the refusals are read as plain HTTP.
    auto c = server.client();
    const auto upgrade = [&](const std::string& target, const std::string& origin, const std::string& host) {
        return c->Get(target.c_str(), {{"Host", host},
                                       {"Origin", origin},
                                       {"Upgrade", "websocket"},
                                       {"Connection", "Upgrade"},
                                       {"Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="},
                                       {"Sec-WebSocket-Version", "13"}});
    };
    const std::string ownHost = "127.0.0.1:" + std::to_string(port);
    const std::vector<std::tuple<std::string, std::string, std::string, int>> refusals{
        {"/api/stream", own, ownHost, 401},
        {withToken, "http://evil.example", ownHost, 403},
        {withToken, own, "evil.example", 421},
        {withToken + "&x=/../etc", own, ownHost, 400}};
    for (const auto& [target, origin, host, status] : refusals) {
        const auto res = upgrade(target, origin, host);
        ASSERT_TRUE(res) << target;
        EXPECT_EQ(res->status, status) << target << " " << origin << " " << host;
        EXPECT_TRUE(bodyJson(res).contains("error")) << res->body;
        WebSocketClient socket(port, target, {{"Origin", origin}}, host);
        EXPECT_FALSE(socket.handshakeOk()) << target << " " << origin << " " << host;
    }
    {
        WebSocketClient socket(port, withToken, {{"Origin", own}});
        EXPECT_TRUE(socket.handshakeOk());
        EXPECT_EQ(socket.response().result_int(), 101u);
        // Without a renderer every view is answered 503, on the open socket.
        ASSERT_TRUE(socket.sendText(viewMessage(1, false)));
        const auto error = socket.read();
        ASSERT_TRUE(error && error->text);
        EXPECT_EQ(nlohmann::json::parse(error->bytes)["status"], 503);
    }
    // A plain GET of the socket's path is no upgrade.
    const auto res = c->Get(withToken.c_str());
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 400);
}

} // namespace
} // namespace vots::test
