// A test world for the server: a temp data folder with two small volumes, a web folder, a cache folder.
#pragma once

#include "LoopbackServer.h"
#include "TempDir.h"

#include <gtest/gtest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

namespace vots::test {

// The two datasets of every test world, from scripts/make-test-volumes: generated Gaussian blobs (uint8,
// 0..255, index space) and a real brain MRI (int16 NIfTI with its patient axes).
inline constexpr const char* BLOBS = "blobs_64x64x64_uint8";
inline constexpr const char* BLOBS_FILE = "blobs_64x64x64_uint8.nrrd";
inline constexpr const char* MRI_BRAIN = "mri-brain_33x41x25_int16";
inline constexpr const char* MRI_BRAIN_FILE = "mri-brain_33x41x25_int16.nii";

/// Owns the folders; makeServer() starts a server over them with the given tweaks.
class ServerWorld {
public:
    ServerWorld() {
        namespace fs = std::filesystem;
        fs::create_directories(data());
        fs::create_directories(web() / "js");
        for (const char* file : {BLOBS_FILE, MRI_BRAIN_FILE})
            fs::create_symlink(fs::path(VOTS_TEST_DATA_DIR) / file, data() / file);
        mDir.write("web/index.html", "<!doctype html><title>Vots</title>");
        mDir.write("web/js/app.js", "console.log('vots');");
        mDir.write("web/style.css", "body{}");
        mDir.write("secret.txt", "outside the web folder");
        fs::create_symlink(mDir.path() / "secret.txt", web() / "link.txt"); // a link out of the web folder
    }

    std::filesystem::path data() const { return mDir.path() / "data"; }
    std::filesystem::path web() const { return mDir.path() / "web"; }
    std::filesystem::path cache() const { return mDir.path() / "cache"; }
    const TempDir& dir() const { return mDir; }

    server::ServerOptions options() const {
        server::ServerOptions o;
        o.dataDirs = {data()};
        o.webDir = web();
        o.cacheDir = cache();
        return o;
    }

    /// options() without a renderer or warm-up fits: a server whose every fit job was asked for by the
    /// test, and whose cache folder holds only those fits' files.
    server::ServerOptions quietOptions() const {
        server::ServerOptions o = options();
        o.withRenderer = false;
        o.warmUpFits = false;
        return o;
    }

private:
    TempDir mDir;
};

/// Parses a response body as JSON; a test failure (not an exception) when it is not.
inline nlohmann::json bodyJson(const httplib::Result& res) {
    if (!res) {
        ADD_FAILURE() << "no response: " << httplib::to_string(res.error());
        return {};
    }
    auto json = nlohmann::json::parse(res->body, nullptr, false);
    if (json.is_discarded()) ADD_FAILURE() << "not JSON: " << res->body.substr(0, 200);
    return json;
}

/// The file's bytes ("" when it cannot be read).
inline std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

/// Runs the real CLI, `vots render 'input' -o 'out' args` (its stderr dropped), expects it to succeed and
/// returns the bytes it wrote: what a server's answer must equal.
inline std::string cliRenderBytes(const std::string& input, const std::string& out, const std::string& args) {
    const std::string command =
        std::string(VOTS_CLI) + " render '" + input + "' -o '" + out + "' " + args + " 2>/dev/null";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    return fileBytes(out);
}

/// Polls /api/jobs/{id} of a POST /api/fit answer until the job is done or failed (about a minute at
/// most); returns the last job JSON.
inline nlohmann::json waitForJob(httplib::Client& c, const nlohmann::json& posted) {
    const std::string path = "/api/jobs/" + std::to_string(posted["job"].get<std::uint64_t>());
    nlohmann::json job;
    for (int i = 0; i < 1200; ++i) {
        job = bodyJson(c.Get(path.c_str()));
        if (job["state"] == "done" || job["state"] == "failed") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return job;
}

/// Polls /api/stats until `until(stats)` holds or four minutes have passed; returns the last stats.
template <class Until> nlohmann::json waitForStats(httplib::Client& c, Until until) {
    // Generous: a warm-up fit runs at nice 19, and under ThreadSanitizer on a busy 2-core machine it took
    // longer than a minute to be scheduled at all.
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::minutes(4);
    nlohmann::json stats;
    while (std::chrono::steady_clock::now() < giveUp) {
        stats = bodyJson(c.Get("/api/stats"));
        if (until(stats)) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return stats;
}

/// One shared server per test suite, so the EGL context and fits are paid once.
class SharedServerTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sWorld = new ServerWorld();
        sServer = new LoopbackServer(sWorld->options());
    }
    static void TearDownTestSuite() {
        delete sServer;
        delete sWorld;
        sServer = nullptr;
        sWorld = nullptr;
    }
    static std::unique_ptr<httplib::Client> client() { return sServer->client(); }
    static ServerWorld& world() { return *sWorld; }

    static inline ServerWorld* sWorld = nullptr;
    static inline LoopbackServer* sServer = nullptr;
};

} // namespace vots::test
