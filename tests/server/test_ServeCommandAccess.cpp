// `vots serve` itself: beyond loopback it generates a token and prints it once on stderr; a --token-file
// token is asked for on loopback too; and no token ever reaches the server's output.
#include "ServeProcess.h"

#include <regex>

namespace vots::test {
namespace {

TEST(ServeCommandAccess, BeyondLoopbackAGeneratedTokenIsPrintedOnceAndRequired) {
    ServerWorld world;
    ServeProcess serve(world, {"--host", "0.0.0.0", "--insecure-http"});
    ASSERT_GT(serve.port(), 0) << serve.output();
    std::smatch m;
    std::string err;
    const std::regex printed("access token: ([0-9a-f]{32})\n");
    for (int i = 0; i < 100 && !std::regex_search(err = serve.err(), m, printed); ++i) // printed after stdout
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(std::regex_search(err, m, printed)) << err;
    const std::string token = m[1].str();
    auto c = serve.client();
    const auto without = c->Get("/api/datasets");
    ASSERT_TRUE(without);
    EXPECT_EQ(without->status, 401);
    const auto with = c->Get("/api/datasets", {{"Authorization", "Bearer " + token}});
    ASSERT_TRUE(with);
    EXPECT_EQ(with->status, 200);
    const auto shell = c->Get("/");
    ASSERT_TRUE(shell);
    EXPECT_EQ(shell->status, 200);
    EXPECT_EQ(serve.stop(), 0);
    // Printed once (the line and the viewer link), never again.
    const std::string all = serve.output();
    std::size_t count = 0;
    for (auto at = all.find(token); at != std::string::npos; at = all.find(token, at + 1))
        ++count;
    EXPECT_EQ(count, 2u) << all;
}

TEST(ServeCommandAccess, ATokenFileIsRequiredOnLoopbackTooAndNeverLogged) {
    ServerWorld world;
    const std::string token = "Zk3-secret_token.0123456789";
    world.dir().write("token", token + "\n");
    ServeProcess serve(world, {"--token-file", world.dir().file("token")});
    ASSERT_GT(serve.port(), 0) << serve.output();
    auto c = serve.client();
    const auto without = c->Get("/api/datasets");
    ASSERT_TRUE(without);
    EXPECT_EQ(without->status, 401);
    // Requests that show it and fail in many ways, so any line about them would carry it.
    const std::string q = "token=" + token;
    for (const std::string& path :
         std::vector<std::string>{"/api/datasets?" + q, "/render?dataset=nope&" + q, "/render?cam=bad&" + q,
                                  "/render?dataset=" + std::string(BLOBS) + "&size=0x0&" + q,
                                  "/api/jobs/999?" + q, "/api/nothing?" + q, "/missing.html?" + q}) {
        const auto res = c->Get(path.c_str(), {{"Authorization", "Bearer " + token}});
        ASSERT_TRUE(res) << path;
        EXPECT_NE(res->status, 401) << path;
        EXPECT_EQ(res->body.find(token), std::string::npos) << path << ": " << res->body;
    }
    const auto badFit =
        c->Post("/api/fit", {{"Authorization", "Bearer " + token}}, "{\"dataset\":1}", "application/json");
    ASSERT_TRUE(badFit);
    EXPECT_EQ(badFit->status, 400);
    EXPECT_EQ(serve.stop(), 0);
    const std::string all = serve.output();
    EXPECT_NE(all.find("token: required"), std::string::npos) << all;
    EXPECT_EQ(all.find(token), std::string::npos) << all;
}

TEST(ServeCommandAccess, AShortTokenFileIsRefused) {
    ServerWorld world;
    world.dir().write("token", "short\n");
    ServeProcess serve(world, {"--token-file", world.dir().file("token")});
    EXPECT_LT(serve.port(), 0);
    EXPECT_EQ(serve.stop(), 2);
    EXPECT_NE(serve.err().find("must be 16..256 characters"), std::string::npos) << serve.err();
}

} // namespace
} // namespace vots::test
