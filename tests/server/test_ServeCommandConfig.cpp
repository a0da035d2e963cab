// `vots serve --config FILE`: a configuration file gives the same server as the same flags, the command line
// overrides the file, and a bad file is a clear start-up error (exit 2).
#include "ServeProcess.h"

namespace vots::test {
namespace {

constexpr const char* VIEWER = "viewer-token-0123456789";
constexpr const char* OPERATOR = "operator-token-0123456789";

/// What a client sees of a server's settings: the roles, the frame cache, the memory budget, the allowed
/// host names, the audit trail, and an image.
struct Observed {
    std::string viewerAccess;
    int statusWithoutToken = 0;
    long long frameCacheBudget = -1;
    int allowedHostStatus = 0, foreignHostStatus = 0;
    std::string budgetLine;
    std::string png;
    bool audited = false;
};

Observed observe(ServeProcess& serve, const std::string& auditLog) {
    Observed o;
    auto c = serve.client();
    const httplib::Headers viewer{{"Authorization", std::string("Bearer ") + VIEWER}};
    const httplib::Headers operatorToken{{"Authorization", std::string("Bearer ") + OPERATOR}};
    if (const auto res = c->Get("/api/access", viewer)) o.viewerAccess = res->body;
    if (const auto res = c->Get("/api/access")) o.statusWithoutToken = res->status;
    const nlohmann::json stats = bodyJson(c->Get("/api/stats", operatorToken));
    if (stats.contains("frameCache"))
        o.frameCacheBudget = stats["frameCache"]["budgetBytes"].get<long long>();
    httplib::Headers named = operatorToken;
    named.emplace("Host", "vots.example");
    if (const auto res = c->Get("/api/datasets", named)) o.allowedHostStatus = res->status;
    named.erase("Host");
    named.emplace("Host", "evil.example");
    if (const auto res = c->Get("/api/datasets", named)) o.foreignHostStatus = res->status;
    const std::string render = std::string("/render?dataset=") + BLOBS + "&size=48x40&cam=az=30,el=20";
    if (const auto res = c->Get(render, operatorToken); res && res->status == 200) o.png = res->body;
    const std::string out = serve.output();
    const auto at = out.find("memory budget:");
    if (at != std::string::npos) o.budgetLine = out.substr(at, out.find('\n', at) - at);
    EXPECT_EQ(serve.stop(), 0) << serve.output();
    o.audited = readWholeFile(auditLog).find("\"action\":\"render\"") != std::string::npos;
    return o;
}

class ServeCommandConfig : public ::testing::Test {
protected:
    ServeCommandConfig() {
        world.dir().write("tokens",
                          std::string("alice viewer ") + VIEWER + "\nbob operator " + OPERATOR + "\n");
    }
    std::string file(const std::string& name) const { return world.dir().file(name); }

    ServerWorld world;
};

TEST_F(ServeCommandConfig, AFileGivesTheSameServerAsTheSameFlags) {
    ServeProcess flags(world,
                       {"--host", "0.0.0.0", "--insecure-http", "--token-file", file("tokens"),
                        "--frame-cache-mb", "3", "--memory-budget", "3G", "--allow-host", "vots.example",
                        "--allow-host", "scanner.example", "--audit-log", file("flags-audit.log")});
    ASSERT_GT(flags.port(), 0) << flags.output();
    const Observed byFlags = observe(flags, file("flags-audit.log"));

    // TOML: comments, quoted strings, a flag as true, a repeatable option as an array.
    world.dir().write("vots.conf",
                      "# vots serve\nhost = \"0.0.0.0\"\ninsecure-http = true\n"
                      "token-file = \"" +
                          file("tokens") +
                          "\"\nframe-cache-mb = 3\n"
                          "memory-budget = 3G\nallow-host = [\"vots.example\", \"scanner.example\"]\n"
                          "audit-log = " +
                          file("file-audit.log") + "\n");
    ServeProcess config(world, {"--config", file("vots.conf")});
    ASSERT_GT(config.port(), 0) << config.output();
    const Observed byFile = observe(config, file("file-audit.log"));

    EXPECT_NE(byFlags.viewerAccess.find("\"viewer\""), std::string::npos) << byFlags.viewerAccess;
    EXPECT_EQ(byFile.viewerAccess, byFlags.viewerAccess);
    EXPECT_EQ(byFlags.statusWithoutToken, 401);
    EXPECT_EQ(byFile.statusWithoutToken, 401);
    EXPECT_EQ(byFlags.frameCacheBudget, 3 << 20);
    EXPECT_EQ(byFile.frameCacheBudget, 3 << 20);
    EXPECT_EQ(byFlags.allowedHostStatus, 200);
    EXPECT_EQ(byFile.allowedHostStatus, 200);
    EXPECT_EQ(byFlags.foreignHostStatus, 421);
    EXPECT_EQ(byFile.foreignHostStatus, 421);
    EXPECT_NE(byFlags.budgetLine.find("3.0 GB"), std::string::npos) << byFlags.budgetLine;
    EXPECT_EQ(byFile.budgetLine, byFlags.budgetLine);
    ASSERT_FALSE(byFlags.png.empty());
    EXPECT_TRUE(byFile.png == byFlags.png) << "the two servers drew different images";
    EXPECT_TRUE(byFlags.audited);
    EXPECT_TRUE(byFile.audited);
}

TEST_F(ServeCommandConfig, TheCommandLineOverridesTheFile) {
    world.dir().write("vots.conf", "frame-cache-mb = 3\nmemory-budget = 3G\n");
    ServeProcess serve(world, {"--config", file("vots.conf"), "--frame-cache-mb", "5"});
    ASSERT_GT(serve.port(), 0) << serve.output();
    const nlohmann::json stats = bodyJson(serve.client()->Get("/api/stats"));
    EXPECT_EQ(stats["frameCache"]["budgetBytes"].get<long long>(), 5 << 20);
    EXPECT_NE(serve.output().find("memory budget: 3.0 GB"), std::string::npos) << serve.output();
    EXPECT_EQ(serve.stop(), 0);
}

TEST_F(ServeCommandConfig, TheHeldFramesBoundIsItsFlagElseAQuarterOfTheBudget) {
    const auto heldFramesBound = [&](const std::vector<std::string>& args) {
        ServeProcess serve(world, args);
        EXPECT_GT(serve.port(), 0) << serve.output();
        const nlohmann::json stats = bodyJson(serve.client()->Get("/api/stats"));
        EXPECT_EQ(serve.stop(), 0);
        return stats["heldFrames"]["boundBytes"].get<long long>();
    };
    EXPECT_EQ(heldFramesBound({"--memory-budget", "4G"}), (4LL << 30) / 4);
    EXPECT_EQ(heldFramesBound({"--memory-budget", "4G", "--held-frames-mb", "7"}), 7LL << 20);
    world.dir().write("vots.conf", "held-frames-mb = 9\n");
    EXPECT_EQ(heldFramesBound({"--config", file("vots.conf")}), 9LL << 20);
}

/// Starts `vots serve --config PATH` and expects exit 2 with `message` as its one line on stderr.
void expectRefused(const ServerWorld& world, const std::string& path, const std::string& message) {
    ServeProcess serve(world, {"--config", path});
    EXPECT_LT(serve.port(), 0) << path;
    EXPECT_EQ(serve.stop(), 2) << path;
    EXPECT_NE(serve.err().find(message), std::string::npos) << serve.err();
    EXPECT_EQ(serve.err().find('\n'), serve.err().size() - 1) << "one line: " << serve.err();
}

TEST_F(ServeCommandConfig, ABadFileIsAClearStartUpError) {
    expectRefused(world, file("missing.conf"), "cannot read the configuration file " + file("missing.conf"));
    expectRefused(world, world.dir().path().string(), "it is a folder");
    struct BadFile {
        std::string text, message;
    };
    for (const auto& [text, message] : std::vector<BadFile>{
             {"frame-cache-mb = 3\ncolour = red\n", "unknown key 'colour'"},
             {"config = other.conf\n", "unknown key 'config'"},
             {"[serve]\nport = 8080\n", "sections are not read"},
             {"frame-cache-mb = 3\nframe-cache-mb = 4\n", "key 'frame-cache-mb' takes one value"},
             {"frame-cache-mb = 99999999\n", "frame-cache-mb"},
             {"renders-per-client = many\n", "renders-per-client"},
             {"tls-cert = " + file("tokens") + "\n", "--tls-cert needs --tls-key"}}) {
        world.dir().write("bad.conf", text);
        expectRefused(world, file("bad.conf"), message);
    }
}

} // namespace
} // namespace vots::test
