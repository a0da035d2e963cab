// The viewer socket's audit trail: a line per still and per refused frame, one line per burst of drafts
// with its frame count, each with /render's fields (who, from where, which dataset, the status) and never
// the token; a log that cannot be written refuses frames (503).
#include "AuditLines.h"
#include "ServerFixture.h"
#include "WebSocketClient.h"

#include <string>
#include <vector>

namespace vots::test {
namespace {

constexpr const char* VIEWER = "stream-viewer-token-0123456789";

std::string view(std::uint64_t seq, bool still, const std::string& cam, const std::string& eps = "") {
    nlohmann::json params{{"dataset", BLOBS}, {"cam", cam}, {"size", "48x32"}};
    if (!eps.empty()) params["eps"] = eps;
    return nlohmann::json{{"type", "view"}, {"seq", seq}, {"still", still}, {"params", params}}.dump();
}

/// Sends the view and reads what answers it: the frame's header (then its image, acknowledged) or an error.
nlohmann::json answerTo(WebSocketClient& socket, const std::string& message) {
    if (!socket.sendText(message)) return {};
    const auto header = socket.read();
    if (!header || !header->text) return {};
    nlohmann::json json = nlohmann::json::parse(header->bytes);
    if (json["type"] == "frame") {
        socket.read(); // the image
        socket.sendText(nlohmann::json{{"type", "ack"}, {"frame", json["frame"]}}.dump());
    }
    return json;
}

class ServerStreamAudit : public ::testing::Test {
protected:
    ServerStreamAudit() {
        server::ServerOptions o = world.options();
        o.warmUpFits = false;
        o.accessTokens = {{"alice", server::Role::Viewer, VIEWER}};
        o.auditLog = log;
        server = std::make_unique<LoopbackServer>(o);
    }
    std::unique_ptr<WebSocketClient> open() const {
        return std::make_unique<WebSocketClient>(
            server->port(), "/api/stream",
            std::map<std::string, std::string>{{"Authorization", std::string("Bearer ") + VIEWER}});
    }
    /// The log's lines once it has `n` (lines are written after their frames are sent).
    std::vector<nlohmann::json> waitForLines(std::size_t n) const {
        for (int i = 0; i < 200 && auditLinesOf(log).size() < n; ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(25));
        return auditLinesOf(log);
    }

    ServerWorld world;
    const std::string log = world.dir().file("audit.log");
    std::unique_ptr<LoopbackServer> server;
};

TEST_F(ServerStreamAudit, AStillALineADragOneLineWithItsFramesARefusalItsOwn) {
    auto socket = open();
    ASSERT_TRUE(socket->handshakeOk()) << socket->handshakeError();
    ASSERT_EQ(answerTo(*socket, view(1, true, "az=10"))["type"], "frame");
    for (std::uint64_t seq = 2; seq <= 4; ++seq) // a drag: three drafts
        ASSERT_EQ(answerTo(*socket, view(seq, false, "az=" + std::to_string(10 * seq)))["type"], "frame");
    ASSERT_EQ(answerTo(*socket, view(5, true, "az=40"))["type"], "frame"); // the drag's end
    // A viewer's token draws no new eps: refused, and audited as refused.
    const nlohmann::json refused = answerTo(*socket, view(6, false, "az=40", "9"));
    ASSERT_EQ(refused["type"], "error");
    EXPECT_EQ(refused["status"], 403);
    for (std::uint64_t seq = 7; seq <= 8; ++seq) // a drag the socket's close ends
        ASSERT_EQ(answerTo(*socket, view(seq, false, "az=" + std::to_string(10 * seq)))["type"], "frame");
    socket.reset();

    const auto lines = waitForLines(5);
    ASSERT_EQ(lines.size(), 5u) << auditTextOf(log);
    const std::vector<std::string> actions{"stream-still", "stream-drafts", "stream-still", "stream-draft",
                                           "stream-drafts"};
    const std::vector<int> statuses{200, 200, 200, 403, 200};
    for (std::size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(lines[i]["action"], actions[i]) << lines[i];
        EXPECT_EQ(lines[i]["status"], statuses[i]) << lines[i];
        EXPECT_EQ(lines[i]["user"], "alice") << lines[i];
        EXPECT_EQ(lines[i]["client"], "127.0.0.1") << lines[i];
        EXPECT_EQ(lines[i]["dataset"], BLOBS) << lines[i];
        EXPECT_EQ(lines[i]["time"].get<std::string>().size(), 24u) << lines[i];
    }
    EXPECT_EQ(lines[1]["frames"], 3);
    EXPECT_EQ(lines[4]["frames"], 2);
    EXPECT_LE(lines[1]["time"].get<std::string>(), lines[1]["until"].get<std::string>());
    EXPECT_EQ(auditTextOf(log).find(VIEWER), std::string::npos);
}

TEST(ServerStreamAuditFull, ALogThatCannotBeWrittenRefusesFrames) {
    ServerWorld world;
    server::ServerOptions o = world.options();
    o.warmUpFits = false;
    o.auditLog = "/dev/full"; // every write fails with ENOSPC
    LoopbackServer server(o);
    WebSocketClient socket(server.port(), "/api/stream");
    ASSERT_TRUE(socket.handshakeOk()) << socket.handshakeError();
    answerTo(socket, view(1, true, "az=10")); // drawn; its line, written after it, fails
    const nlohmann::json refused = answerTo(socket, view(2, false, "az=20"));
    ASSERT_EQ(refused["type"], "error") << refused;
    EXPECT_EQ(refused["status"], 503);
    EXPECT_NE(refused["error"].get<std::string>().find("audit log cannot be written"), std::string::npos);
}

} // namespace
} // namespace vots::test
