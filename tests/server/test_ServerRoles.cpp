// Tokens with roles (`--token-file` lines NAME ROLE TOKEN): a viewer's token is refused (403, JSON) on every
// operator route and an operator's is not, and its frames draw only the fits that exist; GET /api/access
// names the token's role; the file's format.
#include "ServerFixture.h"

#include "vots/fit/Error.h"
#include "vots/server/Exposure.h"

#include <string>

namespace vots::test {
namespace {

constexpr const char* VIEWER = "viewer-token-0123456789";
constexpr const char* OPERATOR = "operator-token-0123456789";

struct OperatorRequest {
    std::string path;
    std::string body;
};

/// Every route only an operator may use, with a body each would take.
std::vector<OperatorRequest> operatorRequests() {
    const std::string store =
        nlohmann::json{{"params", {{"dataset", BLOBS}}}, {"thickness", 1}, {"step", 1}}.dump();
    return {{"/api/fit", nlohmann::json{{"dataset", BLOBS}, {"eps", 9}}.dump()},
            {"/api/pacs/orthanc/store", store},
            {"/api/pacs/stores/1/cancel", "{}"}};
}

/// A server with a viewer's token (alice) and an operator's (bob); with a renderer where frames are drawn.
class RolesServer : public ::testing::Test {
protected:
    explicit RolesServer(bool withRenderer) {
        server::ServerOptions o = world.options();
        o.withRenderer = withRenderer;
        o.warmUpFits = false;
        o.accessTokens = {{"alice", server::Role::Viewer, VIEWER}, {"bob", server::Role::Operator, OPERATOR}};
        server = std::make_unique<LoopbackServer>(o);
    }
    static httplib::Headers bearer(const char* token) {
        return {{"Authorization", std::string("Bearer ") + token}};
    }

    ServerWorld world;
    std::unique_ptr<LoopbackServer> server;
};

class ServerRoles : public RolesServer {
protected:
    ServerRoles() : RolesServer(false) {}
};

class ServerViewerFits : public RolesServer {
protected:
    ServerViewerFits() : RolesServer(true) {}
};

TEST_F(ServerRoles, AViewerTokenIsRefusedOnEveryOperatorRouteAndAnOperatorTokenIsNot) {
    auto c = server->client();
    for (const OperatorRequest& r : operatorRequests()) {
        SCOPED_TRACE(r.path);
        const auto refused = c->Post(r.path.c_str(), bearer(VIEWER), r.body, "application/json");
        ASSERT_TRUE(refused);
        EXPECT_EQ(refused->status, 403) << refused->body;
        EXPECT_EQ(refused->get_header_value("Content-Type"), "application/json");
        EXPECT_NE(bodyJson(refused)["error"].get<std::string>().find("needs an operator's token"),
                  std::string::npos);
        EXPECT_EQ(refused->body.find(VIEWER), std::string::npos);
        const auto allowed = c->Post(r.path.c_str(), bearer(OPERATOR), r.body, "application/json");
        ASSERT_TRUE(allowed);
        EXPECT_NE(allowed->status, 403) << allowed->body;
        EXPECT_NE(allowed->status, 401) << allowed->body;
    }
    // The fit was the operator's: job 1, the viewer's attempt before it made none.
    const auto job = c->Get("/api/jobs/1", bearer(OPERATOR));
    ASSERT_TRUE(job);
    EXPECT_EQ(job->status, 200) << job->body;
    // What a viewer may do stays open to it.
    for (const char* path : {"/api/datasets", "/api/stats", "/api/pacs"}) {
        const auto res = c->Get(path, bearer(VIEWER));
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, 200) << path << ": " << res->body;
    }
}

TEST_F(ServerRoles, AccessNamesTheTokensRoleAndNeverTheToken) {
    auto c = server->client();
    for (const auto& [token, name, role] :
         {std::tuple{VIEWER, "alice", "viewer"}, std::tuple{OPERATOR, "bob", "operator"}}) {
        const auto res = c->Get("/api/access", bearer(token));
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 200);
        const auto json = bodyJson(res);
        EXPECT_EQ(json["name"], name);
        EXPECT_EQ(json["role"], role);
        EXPECT_EQ(json["tokenRequired"], true);
        EXPECT_EQ(res->body.find(token), std::string::npos);
    }
    const auto without = c->Get("/api/access");
    ASSERT_TRUE(without);
    EXPECT_EQ(without->status, 401);
}

// A viewer's token draws the fits that exist (the default eps, an operator's fits) and starts none at a
// new eps, through /render as through POST /api/fit: a 403 that starts no fit job.
TEST_F(ServerViewerFits, AViewerDrawsAnOperatorsFitButStartsNoneAtANewEps) {
    auto c = server->client();
    const std::string newEps = "/render?dataset=" + std::string(BLOBS) + "&size=32x32&eps=9";

    const auto refused = c->Get(newEps, bearer(VIEWER));
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 403) << refused->body;
    EXPECT_EQ(refused->get_header_value("Content-Type"), "application/json");
    EXPECT_NE(bodyJson(refused)["error"].get<std::string>().find("viewer's"), std::string::npos);
    const auto noJob = c->Get("/api/jobs/1", bearer(OPERATOR));
    ASSERT_TRUE(noJob);
    EXPECT_EQ(noJob->status, 404) << "the viewer's render started a fit: " << noJob->body;

    const auto operatorFrame = c->Get(newEps, bearer(OPERATOR));
    ASSERT_TRUE(operatorFrame);
    ASSERT_EQ(operatorFrame->status, 200) << operatorFrame->body;
    const auto viewerFrame = c->Get(newEps, bearer(VIEWER));
    ASSERT_TRUE(viewerFrame);
    ASSERT_EQ(viewerFrame->status, 200) << viewerFrame->body;
    EXPECT_EQ(viewerFrame->body, operatorFrame->body);

    // The default eps is the server's own fit, and the grid needs none: both open to a viewer.
    for (const std::string& path :
         {"/render?dataset=" + std::string(BLOBS) + "&size=32x32",
          "/render?dataset=" + std::string(BLOBS) + "&size=32x32&eps=7&renderer=grid"}) {
        const auto res = c->Get(path, bearer(VIEWER));
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, 200) << path << ": " << res->body;
    }
}

TEST(ServerRolesOpen, WithoutTokensEveryoneIsAnOperator) {
    ServerWorld world;
    LoopbackServer server(world.quietOptions());
    const auto res = server.client()->Get("/api/access");
    ASSERT_TRUE(res);
    EXPECT_EQ(bodyJson(res)["role"], "operator");
    EXPECT_EQ(bodyJson(res)["tokenRequired"], false);
}

TEST(TokenFile, ABareTokenIsAnOperatorAndLinesHaveNamesAndRoles) {
    TempDir dir;
    dir.write("bare", "  " + std::string(OPERATOR) + "\n");
    const auto bare = server::readAccessTokenFile(dir.file("bare"));
    ASSERT_EQ(bare.size(), 1u);
    EXPECT_EQ(bare[0].role, server::Role::Operator);
    EXPECT_EQ(bare[0].token, OPERATOR);

    dir.write("roles", "# who may do what\nalice viewer " + std::string(VIEWER) + "\n\nbob operator " +
                           OPERATOR + "  # on call\n");
    const auto roles = server::readAccessTokenFile(dir.file("roles"));
    ASSERT_EQ(roles.size(), 2u);
    EXPECT_EQ(roles[0].name, "alice");
    EXPECT_EQ(roles[0].role, server::Role::Viewer);
    EXPECT_EQ(roles[0].token, VIEWER);
    EXPECT_EQ(roles[1].name, "bob");
    EXPECT_EQ(roles[1].role, server::Role::Operator);
}

TEST(TokenFile, MalformedFilesAreRefusedWithoutQuotingAToken) {
    TempDir dir;
    const std::string v = VIEWER, o = OPERATOR;
    for (const auto& [content, message] : std::vector<std::pair<std::string, std::string>>{
             {"", "holds no token"},
             {"alice admin " + v + "\n", "the role is viewer or operator"},
             {"alice viewer\n", "expected NAME ROLE TOKEN"},
             {"alice viewer " + v + "\nalice operator " + o + "\n", "repeats"},
             {"alice viewer " + v + "\nbob operator " + v + "\n", "repeats"},
             {"alice viewer short\n", "must be 16..256"},
             {"al!ce viewer " + v + "\n", "a name is"}}) {
        dir.write("tokens", content);
        try {
            server::readAccessTokenFile(dir.file("tokens"));
            ADD_FAILURE() << content;
        } catch (const fit::InputError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(message), std::string::npos) << what;
            EXPECT_EQ(what.find(v), std::string::npos) << what;
            EXPECT_EQ(what.find("short"), std::string::npos) << what;
        }
    }
}

} // namespace
} // namespace vots::test
