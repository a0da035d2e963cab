// A viewer's token draws the fits that exist (the default eps, an operator's fits) and starts none at a new
// eps, through /render as through POST /api/fit: a 403 that starts no fit job.
#include "ServerFixture.h"

#include <string>

namespace vots::test {
namespace {

constexpr const char* VIEWER = "viewer-token-0123456789";
constexpr const char* OPERATOR = "operator-token-0123456789";

class ServerViewerFits : public ::testing::Test {
protected:
    ServerViewerFits() {
        server::ServerOptions o = world.options();
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

} // namespace
} // namespace vots::test
