// A server cache file follows `vots fit`'s meta schema: `vots info` on it reports the fit time and key.
#include "ServerFixture.h"

#include <cstdio>
#include <filesystem>
#include <string>

namespace vots::test {
namespace {

/// Runs the real CLI and returns what it printed on stdout.
std::string cliOutput(const std::string& args) {
    const std::string command = std::string(VOTS_CLI) + " " + args + " 2>/dev/null";
    std::string out;
    if (FILE* pipe = ::popen(command.c_str(), "r")) {
        char buffer[4096];
        while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe))
            out.append(buffer, n);
        EXPECT_EQ(::pclose(pipe), 0) << command;
    }
    return out;
}

TEST(ServerCacheInfo, InfoOfACacheFileShowsItsFitTimeAndKey) {
    ServerWorld world;
    const server::ServerOptions options = world.quietOptions(); // only the requested fit's file in the folder
    LoopbackServer server(options);
    auto c = server.client();
    const auto posted = bodyJson(
        c->Post("/api/fit", R"({"dataset":"mri-brain_33x41x25_int16","eps":"5%"})", "application/json"));
    const auto job = waitForJob(*c, posted);
    ASSERT_EQ(job["state"], "done") << job.dump();
    // The file is written after the fit is announced, at low priority.
    const auto stats = waitForStats(*c, [](const nlohmann::json& s) { return !s["cache"]["disk"].empty(); });
    ASSERT_EQ(stats["cache"]["disk"].size(), 1u) << stats.dump();
    const std::string name = stats["cache"]["disk"][0]["file"];
    const std::string file = (world.cache() / name).string();

    const auto info = nlohmann::json::parse(cliOutput("info --json '" + file + "'"), nullptr, false);
    ASSERT_TRUE(info.is_object()) << "vots info printed no JSON for " << file;
    ASSERT_TRUE(info["fit_seconds"].is_number()) << info.dump();
    EXPECT_NEAR(info["fit_seconds"].get<double>(), job["fitSeconds"].get<double>(), 1e-9);
    EXPECT_EQ(info["meta"]["key"], std::filesystem::path(name).stem().string());
    EXPECT_EQ(info["requested_degree"], 3);
    EXPECT_EQ(info["meta"]["fit"]["certify"], "cells");
    EXPECT_EQ(info["vot_count"], job["votCount"]);

    const std::string text = cliOutput("info '" + file + "'");
    EXPECT_NE(text.find("fit time"), std::string::npos) << text;
}

} // namespace
} // namespace vots::test
