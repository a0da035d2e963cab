// Over loopback: foreign Host names are refused (DNS rebinding), cross-site requests start no fit, and a
// server with a token answers its API only to requests that show it, while the viewer's files stay open.
#include "ServerFixture.h"

#include <string>

namespace vots::test {
namespace {

constexpr const char* TOKEN = "a1b2c3d4e5f6a7b8c9d0e1f2";

std::string fitBody() {
    return nlohmann::json{{"dataset", BLOBS}, {"eps", 9}}.dump();
}

void expectJsonError(const httplib::Result& res, int status, const std::string& what) {
    ASSERT_TRUE(res) << what;
    EXPECT_EQ(res->status, status) << what << ": " << res->body;
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/json") << what;
    const auto json = bodyJson(res);
    EXPECT_TRUE(json.contains("error") && json["error"].is_string()) << what;
    EXPECT_FALSE(res->has_header("Access-Control-Allow-Origin")) << what;
}

TEST(ServerSecurity, ForeignHostNamesAreRefusedBeforeAnyRoute) {
    ServerWorld world;
    server::ServerOptions options = world.quietOptions();
    options.allowedHosts = {"vots.lan", "proxy.lan:8443"};
    LoopbackServer server(options);
    auto c = server.client();
    const std::string port = std::to_string(server.port());
    for (const std::string& host :
         std::vector<std::string>{"evil.example", "evil.example:" + port, "127.0.0.1.evil.example:" + port,
                                  "127.0.0.1:1", "proxy.lan:" + port}) {
        for (const char* path : {"/api/datasets", "/api/stats", "/", "/js/app.js", "/api/jobs/1"})
            expectJsonError(c->Get(path, {{"Host", host}}), 421, host + " " + path);
        expectJsonError(c->Post("/api/fit", {{"Host", host}}, fitBody(), "application/json"), 421, host);
    }
    for (const std::string& host :
         std::vector<std::string>{"127.0.0.1:" + port, "localhost:" + port, "[::1]:" + port, "vots.lan",
                                  "vots.lan:80", "proxy.lan:8443"}) {
        const auto res = c->Get("/api/datasets", {{"Host", host}});
        ASSERT_TRUE(res) << host;
        EXPECT_EQ(res->status, 200) << host;
    }
    // The refused POSTs started nothing: the first real one is job 1.
    const auto res = c->Post("/api/fit", fitBody(), "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 202);
    EXPECT_EQ(bodyJson(res)["job"], 1);
}

TEST(ServerSecurity, CrossSiteRequestsStartNoFitWhileSameOriginOnesDo) {
    ServerWorld world;
    LoopbackServer server(world.quietOptions());
    auto c = server.client();
    const std::string own = "http://127.0.0.1:" + std::to_string(server.port());
    // What a foreign page can send without asking first, or with a foreign Origin.
    expectJsonError(c->Post("/api/fit", fitBody(), "text/plain"), 415, "text/plain");
    expectJsonError(c->Post("/api/fit", {{"Origin", own}}, fitBody(), "text/plain;charset=UTF-8"), 415,
                    "text/plain, same origin");
    expectJsonError(c->Post("/api/fit", "dataset=x", "application/x-www-form-urlencoded"), 415, "form");
    expectJsonError(c->Post("/api/fit", fitBody(), "multipart/form-data; boundary=x"), 415, "multipart");
    expectJsonError(c->Post("/api/fit", {{"Origin", "http://evil.example"}}, fitBody(), "application/json"),
                    403, "foreign Origin");
    expectJsonError(c->Post("/api/fit", {{"Origin", "null"}}, fitBody(), "application/json"), 403,
                    "null Origin");
    expectJsonError(c->Post("/api/fit", {{"Origin", own + "1"}}, fitBody(), "application/json"), 403,
                    "another port");
    expectJsonError(c->Post("/api/fit", {{"Sec-Fetch-Site", "cross-site"}}, fitBody(), "application/json"),
                    403, "Sec-Fetch-Site");
    expectJsonError(c->Put("/api/fit", fitBody(), "text/plain"), 415, "PUT");
    expectJsonError(c->Delete("/api/jobs/1", {{"Origin", "http://evil.example"}}), 403, "DELETE");
    // A foreign page's reads and <img> loads are refused too (they could start fits through /render).
    expectJsonError(c->Get("/api/datasets", {{"Origin", "http://evil.example"}}), 403, "GET, foreign Origin");
    expectJsonError(c->Get("/render?dataset=x", {{"Sec-Fetch-Site", "cross-site"}}), 403, "img from a site");
    expectJsonError(c->Get("/api/datasets", {{"Sec-Fetch-Site", "same-site"}}), 403,
                    "another port, same site");
    const auto stats = bodyJson(c->Get("/api/stats"));
    EXPECT_EQ(stats["fitJobs"]["active"], 0);

    // The viewer's own requests: same Origin, JSON, Sec-Fetch-Site same-origin.
    const auto res = c->Post("/api/fit", {{"Origin", own}, {"Sec-Fetch-Site", "same-origin"}}, fitBody(),
                             "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 202) << res->body;
    EXPECT_EQ(bodyJson(res)["job"], 1); // none of the refused ones became a job
    EXPECT_FALSE(res->has_header("Access-Control-Allow-Origin"));
    const auto typed = c->Post("/api/fit", fitBody(), "application/json; charset=utf-8");
    ASSERT_TRUE(typed);
    EXPECT_EQ(typed->status, 202) << typed->body;
    const auto typed2 = c->Get("/api/datasets", {{"Sec-Fetch-Site", "none"}}); // typed into the address bar
    ASSERT_TRUE(typed2);
    EXPECT_EQ(typed2->status, 200);
}

TEST(ServerSecurity, TokenIsRequiredOnTheApiButNotForTheViewerFiles) {
    ServerWorld world;
    server::ServerOptions options = world.quietOptions();
    options.accessTokens = {{"operator", server::Role::Operator, TOKEN}};
    LoopbackServer server(options);
    auto c = server.client();
    const std::string bearer = std::string("Bearer ") + TOKEN;
    for (const char* path : {"/api/datasets", "/api/stats", "/api/jobs/1", "/api/jobs/1/events",
                             "/render?dataset=blobs_64x64x64_uint8"}) {
        SCOPED_TRACE(path);
        const auto missing = c->Get(path);
        expectJsonError(missing, 401, "no token");
        EXPECT_EQ(missing->get_header_value("WWW-Authenticate"), "Bearer");
        expectJsonError(c->Get(path, {{"Authorization", "Bearer wrong"}}), 401, "wrong token");
        expectJsonError(c->Get(path, {{"Authorization", bearer + "0"}}), 401, "longer token");
        expectJsonError(c->Get(path, {{"Authorization", std::string("Basic ") + TOKEN}}), 401, "not Bearer");
        const std::string sep = std::string(path).find('?') == std::string::npos ? "?" : "&";
        expectJsonError(c->Get((path + sep + "token=" + std::string(TOKEN).substr(1)).c_str()), 401,
                        "wrong query token");
    }
    expectJsonError(c->Post("/api/fit", fitBody(), "application/json"), 401, "POST without token");

    for (const httplib::Headers& headers :
         {httplib::Headers{{"Authorization", bearer}},
          httplib::Headers{{"Authorization", "bearer  " + std::string(TOKEN)}}}) {
        const auto res = c->Get("/api/datasets", headers);
        ASSERT_TRUE(res);
        EXPECT_EQ(res->status, 200);
    }
    const auto query = c->Get((std::string("/api/datasets?token=") + TOKEN).c_str());
    ASSERT_TRUE(query);
    EXPECT_EQ(query->status, 200);
    // token= is no unknown /render parameter: this server has no renderer, so the answer is its 503.
    const auto render = c->Get((std::string("/render?dataset=") + BLOBS + "&token=" + TOKEN).c_str());
    ASSERT_TRUE(render);
    EXPECT_EQ(render->status, 503) << render->body;
    EXPECT_EQ(bodyJson(render)["error"], "rendering is disabled");
    const auto fit = c->Post("/api/fit", {{"Authorization", bearer}}, fitBody(), "application/json");
    ASSERT_TRUE(fit);
    EXPECT_EQ(fit->status, 202);
    const auto job = c->Get((std::string("/api/jobs/1?token=") + TOKEN).c_str());
    ASSERT_TRUE(job);
    EXPECT_EQ(job->status, 200);

    // The viewer shell loads without the token: it reads the token from its URL.
    for (const char* path : {"/", "/index.html", "/js/app.js", "/style.css"}) {
        const auto res = c->Get(path);
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, 200) << path;
    }
    // The Host rule holds for the shell too.
    expectJsonError(c->Get("/", {{"Host", "evil.example"}}), 421, "shell, foreign Host");
}

TEST(ServerSecurity, BoundToEveryInterfaceItAnswersAddressesButNoForeignName) {
    ServerWorld world;
    server::ServerOptions options = world.quietOptions();
    options.accessTokens = {{"operator", server::Role::Operator, TOKEN}};
    LoopbackServer server(options, "0.0.0.0");
    auto c = server.client();
    const std::string port = std::to_string(server.port());
    const httplib::Headers auth{{"Authorization", std::string("Bearer ") + TOKEN}};
    for (const std::string& host :
         std::vector<std::string>{"127.0.0.1:" + port, "192.0.2.7:" + port, "[2001:db8::7]:" + port}) {
        httplib::Headers headers = auth;
        headers.emplace("Host", host);
        const auto res = c->Get("/api/datasets", headers);
        ASSERT_TRUE(res) << host;
        EXPECT_EQ(res->status, 200) << host;
    }
    httplib::Headers foreign = auth;
    foreign.emplace("Host", "evil.example:" + port);
    expectJsonError(c->Get("/api/datasets", foreign), 421, "foreign name");
    expectJsonError(c->Get("/api/datasets"), 401, "no token");
}

} // namespace
} // namespace vots::test
