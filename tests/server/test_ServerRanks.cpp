// The ranks' port (dist::FrameRanks, `vots serve` under mpirun): frames and fits go through it, what it
// refuses is 409, a lost rank is 503, /api/stats shows its ranks, and a viewer's token has the ranks fit
// nothing new; a fake stands for the MPI one.
#include "ServerFixture.h"
#include "WebSocketClient.h"

#include "vots/dist/FrameRanks.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"
#include "vots/render/Png.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <mutex>
#include <optional>
#include <thread>

namespace vots::test {
namespace {

/// Draws a flat image, or throws RanksLost once told a rank is gone; keeps the last requests.
class FakeRanks : public dist::FrameRanks {
public:
    explicit FakeRanks(std::string dataset = MRI_BRAIN) : drawn(std::move(dataset)) {}
    int ranks() const override { return 3; }
    std::string refusal(const std::string& dataset, const render::FrameRequest& frame) const override {
        if (dataset != drawn) return "only " + drawn;
        return frame.mode == render::RenderMode::Density ? "no density" : "";
    }
    dist::ComposedFrame draw(const dist::DrawRequest& request, render::VotRenderer&,
                             render::GridRenderer&) override {
        if (lost) throw dist::RanksLost("rank 2 of 3 did not answer the frame in time");
        std::lock_guard lock(mutex);
        last = request;
        ++frames;
        // The top of the display range: white in the grey map, as one process shows it.
        const std::size_t pixels = static_cast<std::size_t>(request.frame.width * request.frame.height);
        return {{request.frame.width, request.frame.height, std::vector<float>(pixels, 250.f)}, {0.f, 250.f}};
    }
    dist::RanksFit fit(const dist::FitRequest& request, const dist::FitProgress& progress) override {
        if (lost) throw dist::RanksLost("rank 2 of 3 did not answer the fit in time");
        if (progress) { // as rank 0's fit reports; held until the test has seen it
            progress(0.5, "fake fit");
            for (int i = 0; i < 1000 && !releaseFit; ++i)
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        std::lock_guard lock(mutex);
        lastFit = request;
        // The Vots of the three ranks; the slowest took 2 s.
        return {600, 2.0};
    }
    dist::VolumeSummary summarize(const std::filesystem::path& volumePath, int) override {
        std::lock_guard lock(mutex);
        summarized.push_back(volumePath.filename().string());
        return {{0.f, 250.f}, 77u};
    }
    std::vector<dist::RankTimes> lastTimes() const override {
        // Rank 1 fitted for this frame; all three drew from fits that took 1.5, 2 and 1.2 s.
        return {{0, 0.0, 1.0, 0.5, 100, 1500.0},
                {1, 2000.0, 3.0, 4.0, 200, 2000.0},
                {2, 0.0, 5.0, 6.0, 300, 1200.0}};
    }

    const std::string drawn; // the one dataset it draws
    std::atomic<bool> lost{false};
    std::atomic<bool> releaseFit{false}; // lets a fit end
    std::mutex mutex;
    std::optional<dist::DrawRequest> last;
    std::optional<dist::FitRequest> lastFit;
    int frames = 0;
    std::vector<std::string> summarized; // the volume files summarize() was asked for
};

/// True when the PNG is `width` x `height` pixels, every one white and opaque.
bool isWhitePng(const std::string& png, int width, int height) {
    const render::RgbaImage image = render::decodePng(std::vector<std::uint8_t>(png.begin(), png.end()));
    if (image.width != width || image.height != height) return false;
    return std::all_of(image.pixels.begin(), image.pixels.end(), [](std::uint8_t v) { return v == 255; });
}

TEST(ServerRanks, FramesGoThroughItUnfittedRefusalsAre409AndALostRankIs503) {
    ServerWorld world;
    auto ranks = std::make_shared<FakeRanks>();
    server::ServerOptions options = world.options();
    options.ranks = ranks;
    options.warmUpFits = false;
    LoopbackServer server(options);
    auto c = server.client();

    const auto res = c->Get("/render?dataset=mri-brain_33x41x25_int16&cam=az=30,el=20&size=40x30&eps=2%25");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    EXPECT_TRUE(isWhitePng(res->body, 40, 30)) << "the float frame shown over its display range";
    {
        std::lock_guard lock(ranks->mutex);
        ASSERT_TRUE(ranks->last);
        const dist::DrawRequest& asked = *ranks->last;
        EXPECT_EQ(asked.fit.dataset, MRI_BRAIN);
        EXPECT_EQ(asked.fit.volumePath.filename(), std::string(MRI_BRAIN_FILE));
        EXPECT_EQ(asked.frame.width, 40);
        EXPECT_EQ(asked.frame.camera.azimuthDeg, 30.0);
        // The range is the ranks' (summarize), read once: rank 0 loads no samples.
        EXPECT_EQ(asked.fit.valueRange, (std::array<float, 2>{0.f, 250.f}));
        EXPECT_EQ(ranks->summarized, std::vector<std::string>{std::string(MRI_BRAIN_FILE)});
        // 2 % of the whole range, in data units, as every rank resolves it.
        EXPECT_FLOAT_EQ(asked.fit.eps, 0.02f * (asked.fit.valueRange[1] - asked.fit.valueRange[0]));
        EXPECT_FALSE(asked.votsFile);
    }

    // The exact grid goes through it too, as a grid frame (each rank reads its own planes), cached apart.
    const auto grid =
        c->Get("/render?dataset=mri-brain_33x41x25_int16&cam=az=30,el=20&size=40x30&mode=reference");
    ASSERT_TRUE(grid);
    ASSERT_EQ(grid->status, 200) << grid->body;
    {
        std::lock_guard lock(ranks->mutex);
        EXPECT_EQ(ranks->last->frame.renderer, render::RendererKind::Grid);
        EXPECT_EQ(ranks->last->frame.mode, render::RenderMode::Mip);
    }

    nlohmann::json stats = bodyJson(c->Get("/api/stats"));
    EXPECT_EQ(stats["ranks"], 3);
    ASSERT_EQ(stats["rankTimes"].size(), 3u);
    EXPECT_EQ(stats["rankTimes"][1]["rank"], 1);
    EXPECT_EQ(stats["rankTimes"][2]["compositeMs"], 6.0);
    EXPECT_TRUE(stats["fits"].empty()) << "rank 0 fitted the whole volume: " << stats["fits"];
    EXPECT_EQ(stats["rankTimes"][2]["votCount"], 300);

    for (const char* refused : {"/render?dataset=blobs_64x64x64_uint8&size=40x30",
                                "/render?dataset=mri-brain_33x41x25_int16&size=40x30&mode=density"}) {
        const auto no = c->Get(refused);
        ASSERT_TRUE(no);
        EXPECT_EQ(no->status, 409) << refused;
        EXPECT_TRUE(bodyJson(no).contains("error")) << refused;
    }

    // POST /api/fit: the ranks fit (through the port's fit, no frame), rank 0 nothing whole; the job
    // reports all the ranks' Vots and the slowest rank's fit.
    int framesBeforeFit = 0;
    {
        std::lock_guard lock(ranks->mutex);
        framesBeforeFit = ranks->frames;
    }
    const auto post =
        c->Post("/api/fit", R"({"dataset":"mri-brain_33x41x25_int16","eps":"3%"})", "application/json");
    ASSERT_TRUE(post);
    ASSERT_EQ(post->status, 202) << post->body;
    const std::string jobPath = "/api/jobs/" + std::to_string(bodyJson(post)["job"].get<std::uint64_t>());
    nlohmann::json job;
    // While the ranks fit, the job shows the progress rank 0's slab fit reports.
    for (int i = 0; i < 500; ++i) {
        job = bodyJson(c->Get(jobPath.c_str()));
        if (job["stage"] == "fake fit") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_EQ(job["stage"], "fake fit") << job;
    EXPECT_DOUBLE_EQ(job["progress"].get<double>(), 0.5) << job;
    ranks->releaseFit = true;
    for (int i = 0; i < 200; ++i) {
        job = bodyJson(c->Get(jobPath.c_str()));
        if (job["state"] == "done" || job["state"] == "failed") break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ASSERT_EQ(job["state"], "done") << job;
    EXPECT_EQ(job["votCount"], 600);

    EXPECT_DOUBLE_EQ(job["fitSeconds"].get<double>(), 2.0);
    {
        std::lock_guard lock(ranks->mutex);
        ASSERT_TRUE(ranks->lastFit);
        EXPECT_EQ(ranks->frames, framesBeforeFit) << "a fit draws no frame";
        const dist::FitRequest& asked = *ranks->lastFit;
        EXPECT_EQ(asked.dataset, MRI_BRAIN);
        EXPECT_FLOAT_EQ(asked.eps, 0.03f * (asked.valueRange[1] - asked.valueRange[0]));
    }
    EXPECT_TRUE(bodyJson(c->Get("/api/stats"))["fits"].size() == 1u);
    for (const char* refused : {R"({"dataset":"blobs_64x64x64_uint8","eps":"3%"})",
                                R"({"dataset":"mri-brain_33x41x25_int16","eps":"3%",)"
                                R"("focus":{"x":20,"y":20,"z":20,"r":5,"eps":1}})"}) {
        const auto no = c->Post("/api/fit", refused, "application/json");
        ASSERT_TRUE(no);
        EXPECT_EQ(no->status, 409) << refused << ": " << no->body;
    }

    // Only what the ranks draw is listed, its grid read from the file's first plane; other datasets were
    // refused before the ranks read any of them.
    const nlohmann::json listed = bodyJson(c->Get("/api/datasets"))["datasets"];
    ASSERT_EQ(listed.size(), 1u) << listed;
    EXPECT_EQ(listed[0]["name"], MRI_BRAIN);
    EXPECT_EQ(listed[0]["dims"], nlohmann::json::array({33, 41, 25}));
    EXPECT_EQ(listed[0]["range"], nlohmann::json::array({0.0, 250.0}));
    {
        std::lock_guard lock(ranks->mutex);
        EXPECT_EQ(ranks->summarized.size(), 1u);
    }

    ranks->lost = true;
    const auto lost = c->Get("/render?dataset=mri-brain_33x41x25_int16&cam=az=60,el=20&size=40x30");
    ASSERT_TRUE(lost);
    EXPECT_EQ(lost->status, 503);
    EXPECT_EQ(bodyJson(lost)["error"], "rank 2 of 3 did not answer the frame in time");
}

TEST(ServerRanks, AVotsDatasetIsDrawnFromTheFileOnEveryRankAndCountedOnce) {
    ServerWorld world;
    const std::string head = (world.data() / "head.vots").string();
    const std::string fit = std::string(VOTS_CLI) + " fit '" + VOTS_TEST_DATA_DIR + "/" + MRI_BRAIN_FILE +
                            "' -o '" + head + "' --eps 3% 2>/dev/null";
    ASSERT_EQ(std::system(fit.c_str()), 0) << fit;
    const fit::VotSpace file = meta::readVotSpaceFile(head);
    auto ranks = std::make_shared<FakeRanks>("head");
    server::ServerOptions options = world.options();
    options.ranks = ranks;
    options.warmUpFits = false;
    LoopbackServer server(options);
    auto c = server.client();

    const auto res = c->Get("/render?dataset=head&cam=az=30,el=20&size=40x30&mode=minip");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    // The file's Vots, once each, though the fake's ranks say 600 (a box across a slab face is on two).
    EXPECT_EQ(res->get_header_value("X-Vots-Vot-Count"), std::to_string(file.vots.size()));
    {
        std::lock_guard lock(ranks->mutex);
        ASSERT_TRUE(ranks->last);
        const dist::DrawRequest& asked = *ranks->last;
        EXPECT_TRUE(asked.votsFile);
        EXPECT_EQ(asked.fit.volumePath, head);
        EXPECT_EQ(asked.fit.eps, file.eps);
        EXPECT_EQ(asked.frame.mode, render::RenderMode::MinIp);
        EXPECT_TRUE(ranks->summarized.empty()) << "a .vots dataset has no samples for the ranks to sum";
    }
    // What the file cannot give: the grid, another eps, a refit.
    for (const char* refused :
         {"/render?dataset=head&size=40x30&renderer=grid", "/render?dataset=head&size=40x30&eps=1%25"}) {
        const auto no = c->Get(refused);
        ASSERT_TRUE(no);
        EXPECT_EQ(no->status, 409) << refused << ": " << no->body;
    }
    const auto refit = c->Post("/api/fit", R"({"dataset":"head","eps":"1%"})", "application/json");
    ASSERT_TRUE(refit);
    EXPECT_EQ(refit->status, 409) << refit->body;
}

// Under mpirun the ranks fit a new eps before they draw it: a viewer's token gets 403 through /render,
// /turntable and the socket, and the ranks are asked for nothing, until an operator has the ranks fit it.
TEST(ServerRanks, AViewersTokenHasTheRanksFitNothingNew) {
    ServerWorld world;
    auto ranks = std::make_shared<FakeRanks>();
    ranks->releaseFit = true;
    server::ServerOptions options = world.options();
    options.ranks = ranks;
    options.warmUpFits = false;
    const std::string viewer = "viewer-token-0123456789", operatorToken = "operator-token-0123456789";
    options.accessTokens = {{"alice", server::Role::Viewer, viewer},
                            {"bob", server::Role::Operator, operatorToken}};
    LoopbackServer server(options);
    auto c = server.client();
    const httplib::Headers asViewer{{"Authorization", "Bearer " + viewer}};
    const httplib::Headers asOperator{{"Authorization", "Bearer " + operatorToken}};
    const std::string view = std::string("dataset=") + MRI_BRAIN + "&cam=az=30,el=20&size=40x30";

    for (const std::string& path :
         {"/render?" + view + "&eps=7%25", "/turntable?" + view + "&eps=7%25&frames=2"}) {
        const auto refused = c->Get(path, asViewer);
        ASSERT_TRUE(refused) << path;
        EXPECT_EQ(refused->status, 403) << path << ": " << refused->body;
        EXPECT_NE(bodyJson(refused)["error"].get<std::string>().find("viewer's"), std::string::npos);
    }
    WebSocketClient socket(server.port(), "/api/stream?token=" + viewer);
    ASSERT_TRUE(socket.handshakeOk()) << socket.handshakeError();
    ASSERT_TRUE(socket.sendText(nlohmann::json{
        {"type", "view"},
        {"seq", 1},
        {"still", true},
        {"params", {{"dataset", MRI_BRAIN}, {"cam", "az=30,el=20"}, {"size", "40x30"}, {"eps", "7%"}}}}
                                    .dump()));
    const auto error = socket.read();
    ASSERT_TRUE(error && error->text) << "close code " << socket.closeCode();
    EXPECT_EQ(nlohmann::json::parse(error->bytes)["status"], 403) << error->bytes;
    {
        std::lock_guard lock(ranks->mutex);
        EXPECT_EQ(ranks->frames, 0) << "a viewer's frame reached the ranks";
        EXPECT_FALSE(ranks->lastFit) << "a viewer's frame had the ranks fit";
    }

    // The default eps is the server's own fit: open to a viewer.
    const auto first = c->Get("/render?" + view, asViewer);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->status, 200) << first->body;

    // An operator has the ranks fit 7 %; then the viewer draws it.
    const auto job =
        c->Post("/api/fit", asOperator, nlohmann::json{{"dataset", MRI_BRAIN}, {"eps", "7%"}}.dump(),
                "application/json");
    ASSERT_TRUE(job);
    ASSERT_EQ(job->status, 202) << job->body;
    const std::string jobPath = "/api/jobs/" + std::to_string(bodyJson(job)["job"].get<int>());
    std::string state;
    for (int i = 0; i < 600 && state != "done" && state != "failed"; ++i) {
        state = bodyJson(c->Get(jobPath, asOperator))["state"].get<std::string>();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_EQ(state, "done");
    const auto drawn = c->Get("/render?" + view + "&eps=7%25", asViewer);
    ASSERT_TRUE(drawn);
    EXPECT_EQ(drawn->status, 200) << drawn->body;
}

} // namespace
} // namespace vots::test
