// The audit trail (`--audit-log`): one JSON line per access to patient data with who, from where, what and
// the status, never a token; rotated by size; a log that cannot be written makes data requests 503.
#include "AuditLines.h"
#include "ServerFixture.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

namespace vots::test {
namespace {

constexpr const char* TOKEN = "audit-viewer-token-0123456789";

server::ServerOptions auditedOptions(const ServerWorld& world, const std::string& log) {
    server::ServerOptions o = world.quietOptions();
    o.accessTokens = {{"alice", server::Role::Operator, TOKEN}};
    o.auditLog = log;
    return o;
}

httplib::Headers bearer() {
    return {{"Authorization", std::string("Bearer ") + TOKEN}};
}

TEST(ServerAudit, OneLinePerDataAccessWithWhoWhatAndStatusAndNoToken) {
    ServerWorld world;
    const std::string log = world.dir().file("audit.log");
    {
        LoopbackServer server(auditedOptions(world, log));
        auto c = server.client();
        ASSERT_EQ(c->Get("/api/datasets", bearer())->status, 200);
        c->Get((std::string("/render?dataset=") + BLOBS + "&token=" + TOKEN).c_str());
        c->Get((std::string("/turntable?dataset=") + BLOBS).c_str(), bearer());
        const std::string fit = nlohmann::json{{"dataset", BLOBS}, {"eps", 9}}.dump();
        ASSERT_EQ(c->Post("/api/fit", bearer(), fit, "application/json")->status, 202);
        c->Get("/api/pacs/none/studies/1.2.3/series", bearer());
        c->Post("/api/pacs/none/studies/1.2.3/series/4.5.6/open", bearer(), "{}", "application/json");
        ASSERT_EQ(c->Get("/api/datasets")->status, 401);        // refused: audited with no user
        ASSERT_EQ(c->Get("/api/stats", bearer())->status, 200); // no patient data: not audited
    }
    // Each line is written after its answer, so two close requests may be logged in either order.
    const auto lines = auditLinesOf(log);
    ASSERT_EQ(lines.size(), 7u);
    std::map<std::string, std::vector<nlohmann::json>> byAction;
    for (const auto& line : lines) {
        EXPECT_EQ(line["client"], "127.0.0.1");
        EXPECT_TRUE(line["time"].is_string() && line["time"].get<std::string>().size() == 24) << line;
        EXPECT_TRUE(line["status"].is_number_integer());
        byAction[line["action"]].push_back(line);
    }
    for (const char* action : {"render", "turntable", "fit", "pacs-query", "pacs-retrieve"}) {
        ASSERT_EQ(byAction[action].size(), 1u) << action;
        EXPECT_EQ(byAction[action][0]["user"], "alice") << action;
    }
    ASSERT_EQ(byAction["list-datasets"].size(), 2u);
    std::set<nlohmann::json> listings{byAction["list-datasets"][0], byAction["list-datasets"][1]};
    EXPECT_EQ(std::count_if(listings.begin(), listings.end(),
                            [](const auto& l) { return l["status"] == 200 && l["user"] == "alice"; }),
              1);
    EXPECT_EQ(std::count_if(listings.begin(), listings.end(),
                            [](const auto& l) { return l["status"] == 401 && l["user"].is_null(); }),
              1);
    EXPECT_EQ(byAction["render"][0]["dataset"], BLOBS);
    EXPECT_EQ(byAction["fit"][0]["dataset"], BLOBS);
    EXPECT_EQ(byAction["fit"][0]["status"], 202);
    EXPECT_EQ(byAction["pacs-query"][0]["study"], "1.2.3");
    EXPECT_EQ(byAction["pacs-retrieve"][0]["study"], "1.2.3");
    EXPECT_EQ(byAction["pacs-retrieve"][0]["series"], "4.5.6");
    EXPECT_EQ(auditTextOf(log).find(TOKEN), std::string::npos);
}

TEST(ServerAudit, TheLogIsRotatedBySize) {
    ServerWorld world;
    const std::string log = world.dir().file("audit.log");
    server::ServerOptions o = auditedOptions(world, log);
    o.auditLogBytes = 400; // about three lines
    LoopbackServer server(o);
    auto c = server.client();
    for (int i = 0; i < 10; ++i)
        ASSERT_EQ(c->Get("/api/datasets", bearer())->status, 200);
    const auto current = auditLinesOf(log), previous = auditLinesOf(log + ".1");
    EXPECT_FALSE(previous.empty());
    EXPECT_LT(current.size(), 10u);
    EXPECT_LE(std::filesystem::file_size(log + ".1"), 400u + 200u);
    EXPECT_EQ(previous.back()["action"], "list-datasets");
}

TEST(ServerAudit, AFullDiskMakesDataRequests503) {
    ServerWorld world;
    LoopbackServer server(auditedOptions(world, "/dev/full")); // every write fails with ENOSPC
    auto c = server.client();
    c->Get("/api/datasets", bearer()); // answered; its line, written after the answer, fails
    int status = 0;
    std::string body;
    for (int i = 0; i < 100 && status != 503; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        const auto res = c->Get("/api/datasets", bearer());
        ASSERT_TRUE(res);
        status = res->status;
        body = res->body;
    }
    EXPECT_EQ(status, 503);
    EXPECT_NE(body.find("audit log cannot be written"), std::string::npos) << body;
    EXPECT_EQ(c->Get("/api/stats", bearer())->status, 200); // no patient data: still answered
}

} // namespace
} // namespace vots::test
