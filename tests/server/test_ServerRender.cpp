// GET /render over loopback: same bytes as `vots render`, headers, concurrent clients (superseded frames:
// test_ServerSupersede.cpp).
#include "ServerFixture.h"

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace vots::test {
namespace {

class ServerRender : public SharedServerTest {
protected:
    /// Runs the real CLI and returns the PNG bytes it wrote: fitted by the server's norm (SERVE_FIT_NORM),
    /// unless args name one.
    static std::string cliRender(const std::string& file, const std::string& args) {
        const std::string out = world().dir().file("cli-" + std::to_string(sCount++) + ".png");
        const std::string norm =
            args.find("--fit-norm") == std::string::npos
                ? std::string(" --fit-norm ") + std::string(fit::nameOf(fit::SERVE_FIT_NORM))
                : std::string();
        return cliRenderBytes(std::string(VOTS_TEST_DATA_DIR) + "/" + file, out, args + norm);
    }
    static std::string serverRender(const std::string& query) {
        const auto res = client()->Get(("/render?" + query).c_str());
        if (!res) return "no response";
        EXPECT_EQ(res->status, 200) << query << ": " << res->body;
        EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
        return res->body;
    }
    static inline int sCount = 0;
};

TEST_F(ServerRender, MipMatchesCliBytes) {
    const std::string png = serverRender("dataset=blobs_64x64x64_uint8&cam=az=30,el=20&size=128x96&eps=2%25");
    EXPECT_EQ(png, cliRender(BLOBS_FILE, "--cam az=30,el=20 --size 128x96 --eps 2%"));
}

TEST_F(ServerRender, WindowColormapAndDegreeMatchCliBytes) {
    const std::string png = serverRender("dataset=mri-brain_33x41x25_int16&cam=view%3Dleft&size=96x96&eps="
                                         "8&degree=2&window=100,150&colormap=hot");
    EXPECT_EQ(png,
              cliRender(MRI_BRAIN_FILE,
                        "--cam view=left --size 96x96 --eps 8 --degree 2 --window 100,150 --colormap hot"));
}

TEST_F(ServerRender, ProjectionsAndSlabsMatchCliBytesAndAreCachedApart) {
    const std::string base = "dataset=blobs_64x64x64_uint8&cam=az=30,el=20&size=80x80&eps=2%25";
    const std::string minip = serverRender(base + "&mode=minip");
    const std::string aip = serverRender(base + "&mode=aip");
    const std::string slab = serverRender(base + "&mode=aip&slab=5,12");
    EXPECT_EQ(minip, cliRender(BLOBS_FILE, "--cam az=30,el=20 --size 80x80 --eps 2% --mode minip"));
    EXPECT_EQ(aip, cliRender(BLOBS_FILE, "--cam az=30,el=20 --size 80x80 --eps 2% --mode aip"));
    EXPECT_EQ(slab, cliRender(BLOBS_FILE, "--cam az=30,el=20 --size 80x80 --eps 2% --mode aip --slab 5,12"));
    EXPECT_NE(minip, aip);
    EXPECT_NE(aip, slab);
    EXPECT_NE(serverRender(base), minip); // mip, not a cached minip
}

TEST_F(ServerRender, DensityAndReferenceMatchCliBytes) {
    EXPECT_EQ(serverRender("dataset=blobs_64x64x64_uint8&size=80x80&eps=3%25&mode=density"),
              cliRender(BLOBS_FILE, "--size 80x80 --eps 3% --mode density"));
    EXPECT_EQ(
        serverRender("dataset=blobs_64x64x64_uint8&cam=az=-40,el=10,zoom=1.5&size=80x80&mode=reference"),
        cliRender(BLOBS_FILE, "--cam az=-40,el=10,zoom=1.5 --size 80x80 --mode reference"));
}

TEST_F(ServerRender, RefitAtNewEpsThroughBoxCacheMatchesCliBytes) {
    // The first fit fills the per-(dataset, degree) box cache; the second reuses it and must not differ.
    serverRender("dataset=blobs_64x64x64_uint8&size=32x32&eps=7%25");
    EXPECT_EQ(serverRender("dataset=blobs_64x64x64_uint8&size=64x64&eps=4%25&cam=superior"),
              cliRender(BLOBS_FILE, "--size 64x64 --eps 4% --cam superior"));
}

TEST_F(ServerRender, AMinimaxServerRefitsThroughItsBoxCacheToTheCliBytes) {
    // `vots serve --fit-norm minimax`: its fits, refits from the box cache included, are `vots render
    // --fit-norm minimax`'s, and the key tells them from least squares'.
    server::ServerOptions options = world().options();
    options.fitNorm = fit::FitNorm::Minimax;
    options.cacheDir.clear();
    const LoopbackServer minimax(options);
    const auto render = [&](const std::string& query) {
        const auto res = minimax.client()->Get(("/render?" + query).c_str());
        return res && res->status == 200 ? res->body : std::string("failed");
    };
    render("dataset=blobs_64x64x64_uint8&size=32x32&eps=7%25");
    const std::string refit = render("dataset=blobs_64x64x64_uint8&size=64x64&eps=4%25&cam=superior");
    EXPECT_EQ(refit, cliRender(BLOBS_FILE, "--size 64x64 --eps 4% --cam superior --fit-norm minimax"));
    EXPECT_NE(refit, cliRender(BLOBS_FILE, "--size 64x64 --eps 4% --cam superior --fit-norm lsq"));
}

TEST_F(ServerRender, SameUrlSameBytesAndHeaders) {
    const std::string query = "/render?dataset=blobs_64x64x64_uint8&size=64x64&cam=az=33";
    auto c = client();
    const auto a = c->Get(query.c_str());
    const auto b = c->Get(query.c_str());
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->status, 200) << a->body;
    EXPECT_EQ(a->body, b->body);
    EXPECT_EQ(a->get_header_value("X-Vots-Frame-Cache"), "miss");
    EXPECT_EQ(b->get_header_value("X-Vots-Frame-Cache"), "hit"); // the same request, answered again
    EXPECT_EQ(a->get_header_value("X-Vots-Frame-Ms"), b->get_header_value("X-Vots-Frame-Ms"));
    EXPECT_GT(std::stoi(a->get_header_value("X-Vots-Vot-Count")), 0);
    EXPECT_GT(std::stod(a->get_header_value("X-Vots-Frame-Ms")), 0.0);
    EXPECT_GE(std::stod(a->get_header_value("X-Vots-Fit-Seconds")), 0.0);
    EXPECT_EQ(a->body.substr(1, 3), "PNG");
}

TEST_F(ServerRender, AFrameThatBeginsWithAnUploadSaysSoTheNextNone) {
    // A server of its own: what its render thread has uploaded depends on this test's requests alone.
    server::ServerOptions options = world().options();
    options.cacheDir.clear();
    const LoopbackServer own(options);
    const auto uploadAndFrameMs = [&](const std::string& query) {
        const auto res =
            own.client()->Get(("/render?dataset=blobs_64x64x64_uint8&size=48x48&" + query).c_str());
        EXPECT_TRUE(res && res->status == 200) << query;
        if (!res || res->status != 200) return std::pair{-1.0, -1.0};
        EXPECT_GE(std::stod(res->get_header_value("X-Vots-Encode-Ms")), 0.0);
        return std::pair{std::stod(res->get_header_value("X-Vots-Upload-Ms")),
                         std::stod(res->get_header_value("X-Vots-Frame-Ms"))};
    };
    // Each fit is uploaded as it is made (its frames then find it there). The render thread holds two:
    // going back to the first one after two more, still in memory, is a frame that uploads it again.
    EXPECT_EQ(uploadAndFrameMs("eps=5%25&cam=az=10").first, 0.0);
    EXPECT_EQ(uploadAndFrameMs("eps=3%25&cam=az=10").first, 0.0);
    EXPECT_EQ(uploadAndFrameMs("eps=4%25&cam=az=10").first, 0.0);
    const auto [upload, frame] = uploadAndFrameMs("eps=5%25&cam=az=20");
    EXPECT_GT(upload, 0.0);
    EXPECT_LE(upload, frame); // a part of the frame's time
    EXPECT_EQ(uploadAndFrameMs("eps=5%25&cam=az=30").first, 0.0);
}

TEST_F(ServerRender, ARequestedFitIsUploadedBeforeItsFirstFrameIsAskedFor) {
    server::ServerOptions options = world().options();
    options.cacheDir.clear();
    const LoopbackServer own(options);
    auto c = own.client();
    const std::string query = "/render?dataset=blobs_64x64x64_uint8&size=40x40&cam=az=15&eps=6%25";
    const auto first = c->Get(query.c_str());
    ASSERT_TRUE(first && first->status == 200);
    const int framesBefore = bodyJson(c->Get("/api/stats"))["frames"]["count"].get<int>();

    // As the viewer's eps slider does: the fit, then its first frame once the job is done.
    const auto posted = bodyJson(
        c->Post("/api/fit", R"({"dataset":"blobs_64x64x64_uint8","eps":"3.5%"})", "application/json"));
    ASSERT_EQ(waitForJob(*c, posted)["state"], "done");
    // The upload's own small frame, queued by the fit before it was announced done.
    const auto stats = waitForStats(
        *c, [&](const nlohmann::json& s) { return s["frames"]["count"].get<int>() > framesBefore; });
    EXPECT_EQ(stats["frames"]["count"].get<int>(), framesBefore + 1);
    const auto refitted = c->Get("/render?dataset=blobs_64x64x64_uint8&size=40x40&cam=az=15&eps=3.5%25");
    ASSERT_TRUE(refitted && refitted->status == 200);
    EXPECT_EQ(std::stod(refitted->get_header_value("X-Vots-Upload-Ms")), 0.0);
    EXPECT_NE(refitted->body, first->body);
}

TEST_F(ServerRender, WithoutFrameCacheTheSameUrlRendersAgainToTheSameBytes) {
    server::ServerOptions options = world().options();
    options.frameCacheBytes = 0;
    options.cacheDir.clear();
    const LoopbackServer uncached(options);
    const std::string query = "/render?dataset=blobs_64x64x64_uint8&size=48x40&cam=az=-70,el=35";
    const auto a = uncached.client()->Get(query.c_str());
    const auto b = uncached.client()->Get(query.c_str());
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->status, 200) << a->body;
    EXPECT_EQ(a->get_header_value("X-Vots-Frame-Cache"), "miss");
    EXPECT_EQ(b->get_header_value("X-Vots-Frame-Cache"), "miss");
    EXPECT_EQ(a->body, b->body); // rendered twice, byte for byte the same
    EXPECT_EQ(a->body, serverRender(query.substr(8)));
}

TEST_F(ServerRender, FrameCacheTellsWindowsApartToTheLastBit) {
    const std::string base = "/render?dataset=blobs_64x64x64_uint8&size=40x40&cam=az=-5&window=100";
    auto c = client();
    const auto a = c->Get((base + ",50").c_str());
    const auto b = c->Get((base + ".0001,50").c_str()); // the same to 3 decimals, another float
    const auto again = c->Get((base + ",50").c_str());
    ASSERT_TRUE(a && b && again);
    ASSERT_EQ(a->status, 200) << a->body;
    EXPECT_EQ(a->get_header_value("X-Vots-Frame-Cache"), "miss");
    EXPECT_EQ(b->get_header_value("X-Vots-Frame-Cache"), "miss");
    EXPECT_EQ(again->get_header_value("X-Vots-Frame-Cache"), "hit");
}

TEST_F(ServerRender, IdenticalRequestsAtOnceRenderOnce) {
    const std::string query = "/render?dataset=blobs_64x64x64_uint8&size=96x96&cam=az=71,el=-12";
    serverRender("dataset=blobs_64x64x64_uint8&size=8x8"); // fitted already
    const auto before = bodyJson(client()->Get("/api/stats"))["frameCache"];
    std::vector<std::future<std::string>> fetches;
    for (int i = 0; i < 4; ++i)
        fetches.push_back(std::async(std::launch::async, [&] {
            const auto res = client()->Get(query.c_str());
            return res && res->status == 200 ? res->body : std::string("failed");
        }));
    std::vector<std::string> bodies;
    for (auto& f : fetches)
        bodies.push_back(f.get());
    for (const std::string& body : bodies)
        EXPECT_EQ(body, bodies.front());
    EXPECT_NE(bodies.front(), "failed");
    const auto after = bodyJson(client()->Get("/api/stats"))["frameCache"];
    EXPECT_EQ(after["rendered"].get<int>() - before["rendered"].get<int>(), 1);
    EXPECT_EQ(after["shared"].get<int>() + after["cached"].get<int>() - before["shared"].get<int>() -
                  before["cached"].get<int>(),
              3);
}

TEST_F(ServerRender, TwoClientsAtOnceGetTheirOwnImages) {
    const std::string left = "/render?dataset=blobs_64x64x64_uint8&size=64x64&cam=left&client=a";
    const std::string right = "/render?dataset=blobs_64x64x64_uint8&size=64x64&cam=right&client=b";
    auto fetch = [](const std::string& path) {
        const auto res = client()->Get(path.c_str());
        return res && res->status == 200 ? res->body : std::string("failed");
    };
    auto a = std::async(std::launch::async, fetch, left);
    auto b = std::async(std::launch::async, fetch, right);
    const std::string pngA = a.get();
    const std::string pngB = b.get();
    EXPECT_EQ(pngA, fetch(left));
    EXPECT_EQ(pngB, fetch(right));
    EXPECT_NE(pngA, pngB);
}

} // namespace
} // namespace vots::test
