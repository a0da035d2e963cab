// The JSON endpoints over loopback: datasets, stats, static files, fit jobs with polling and SSE, limits.
#include "ServerFixture.h"

#include "vots/render/EglContext.h"

#include <chrono>
#include <thread>

namespace vots::test {
namespace {

class ServerApi : public SharedServerTest {};

TEST_F(ServerApi, ListsDatasetsWithGridRangeAndPresets) {
    const auto res = client()->Get("/api/datasets");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
    const auto json = bodyJson(res);
    ASSERT_EQ(json["datasets"].size(), 2u);
    const auto& brain = json["datasets"][1]; // sorted by name: blobs... < mri-brain...
    EXPECT_EQ(brain["name"], MRI_BRAIN);
    EXPECT_EQ(brain["dims"], nlohmann::json::array({33, 41, 25}));
    EXPECT_EQ(brain["modality"], "other");
    const auto& blobs = json["datasets"][0];
    EXPECT_EQ(blobs["name"], BLOBS);
    EXPECT_EQ(blobs["range"], nlohmann::json::array({0.0, 255.0}));
    EXPECT_FLOAT_EQ(blobs["defaultEps"].get<float>(), 5.1f);
    EXPECT_FLOAT_EQ(blobs["background"].get<float>(), 2.55f);
    EXPECT_FLOAT_EQ(blobs["window"]["level"].get<float>(), 127.5f);
    EXPECT_FLOAT_EQ(blobs["window"]["width"].get<float>(), 255.f);
    for (const char* preset : {"bone", "soft", "full"}) {
        ASSERT_TRUE(blobs["presets"].contains(preset)) << preset;
        EXPECT_GT(blobs["presets"][preset]["width"].get<float>(), 0.f);
    }
}

TEST_F(ServerApi, ServesStaticFilesWithContentTypes) {
    auto c = client();
    auto res = c->Get("/");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Content-Type"), "text/html; charset=utf-8");
    EXPECT_NE(res->body.find("Vots"), std::string::npos);
    res = c->Get("/js/app.js");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
    EXPECT_EQ(res->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
    res = c->Get("/style.css");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->get_header_value("Content-Type"), "text/css; charset=utf-8");
}

TEST_F(ServerApi, RefusesFilesOutsideTheWebFolder) {
    auto c = client();
    for (const char* path : {"/link.txt", "/missing.html", "/js/"}) {
        const auto res = c->Get(path);
        ASSERT_TRUE(res) << path;
        EXPECT_EQ(res->status, 404) << path;
        EXPECT_TRUE(bodyJson(res).contains("error")) << path;
    }
}

TEST_F(ServerApi, UnknownApiPathIsJson404) {
    const auto res = client()->Get("/api/nothing");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 404);
    EXPECT_TRUE(bodyJson(res).contains("error"));
}

TEST_F(ServerApi, FitJobRunsFromPostToSseDone) {
    auto c = client();
    const auto post = c->Post("/api/fit", R"({"dataset":"mri-brain_33x41x25_int16","eps":"3%","degree":2})",
                              "application/json");
    ASSERT_TRUE(post);
    ASSERT_EQ(post->status, 202) << post->body;
    const auto job = bodyJson(post);
    ASSERT_TRUE(job["job"].is_number_unsigned());
    const auto id = job["job"].get<std::uint64_t>();
    EXPECT_EQ(job["degree"], 2);

    std::string stream;
    const auto events = c->Get(("/api/jobs/" + std::to_string(id) + "/events").c_str(),
                               [&stream](const char* data, std::size_t length) {
                                   stream.append(data, length);
                                   return true;
                               });
    ASSERT_TRUE(events);
    EXPECT_EQ(events->status, 200);
    EXPECT_EQ(events->get_header_value("Content-Type"), "text/event-stream");
    EXPECT_NE(stream.find("event: progress\ndata: {"), std::string::npos) << stream;
    const auto done = stream.find("event: done\ndata: ");
    ASSERT_NE(done, std::string::npos) << stream;
    const auto data =
        nlohmann::json::parse(stream.substr(done + 18, stream.find('\n', done + 18) - done - 18));
    EXPECT_EQ(data["state"], "done");
    EXPECT_GT(data["votCount"].get<int>(), 0);
    EXPECT_GE(data["fitSeconds"].get<double>(), 0.0);

    const auto polled = bodyJson(c->Get(("/api/jobs/" + std::to_string(id)).c_str()));
    EXPECT_EQ(polled["state"], "done");
    EXPECT_EQ(polled["progress"], 1.0);
    EXPECT_EQ(polled["votCount"], data["votCount"]);
    EXPECT_TRUE(polled["error"].is_null());

    // The same key again reuses the fitted Vot-Space: done at once, same Vot count.
    const auto again = bodyJson(c->Post(
        "/api/fit", R"({"dataset":"mri-brain_33x41x25_int16","eps":"3%","degree":2})", "application/json"));
    EXPECT_EQ(again["state"], "done");
    EXPECT_EQ(again["votCount"], data["votCount"]);
}

TEST_F(ServerApi, FocusFitCompletes) {
    auto c = client();
    const auto post = c->Post(
        "/api/fit",
        R"({"dataset":"mri-brain_33x41x25_int16","eps":2480,"focus":{"x":16,"y":20,"z":12,"r":8,"eps":620}})",
        "application/json");
    ASSERT_TRUE(post);
    ASSERT_EQ(post->status, 202) << post->body;
    const nlohmann::json job = waitForJob(*c, bodyJson(post));
    EXPECT_EQ(job["state"], "done") << job.dump();
    EXPECT_NE(job["key"].get<std::string>().find("_f"), std::string::npos);
}

TEST_F(ServerApi, StatsReportFramesFitsAndCaches) {
    auto c = client();
    const auto png = c->Get("/render?dataset=mri-brain_33x41x25_int16&size=64x64&eps=4%25");
    ASSERT_TRUE(png);
    ASSERT_EQ(png->status, 200) << png->body;
    auto stats = bodyJson(c->Get("/api/stats"));
    // The cache file is written after the fit is announced, at low priority: give it a while.
    for (int i = 0; i < 200 && stats["cache"]["disk"].empty(); ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        stats = bodyJson(c->Get("/api/stats"));
    }
    EXPECT_GE(stats["frames"]["count"].get<int>(), 1);
    EXPECT_GT(stats["frames"]["lastMs"].get<double>(), 0.0);
    EXPECT_GT(stats["frames"]["medianMs"].get<double>(), 0.0);
    EXPECT_GE(stats["fits"].size(), 1u);
    EXPECT_GT(stats["fits"].back()["votCount"].get<int>(), 0);
    EXPECT_GE(stats["cache"]["memory"].size(), 1u);
    EXPECT_GE(stats["cache"]["disk"].size(), 1u);
    EXPECT_TRUE(stats["cache"]["diskEnabled"].get<bool>());
    EXPECT_TRUE(stats["renderer"].contains("available"));
    // llvmpipe walks on the rasteriser, a GPU in a compute shader (bench/RESULTS.md, "GPU").
    const std::string name = stats["renderer"]["name"];
    EXPECT_EQ(stats["renderer"]["walkShader"],
              render::EglContext::isSoftwareRenderer(name) ? "fragment" : "compute");
}

TEST(ServerLimits, TooManyFitJobsGive429) {
    ServerWorld world;
    auto options = world.options();
    options.maxRunningFits = 1;
    options.maxQueuedFits = 1;
    options.withRenderer = false;
    LoopbackServer server(options);
    auto c = server.client();
    int accepted = 0;
    int refused = 0;
    for (int i = 1; i <= 6; ++i) { // tight eps: each fit takes a while, so the queue fills
        const std::string body =
            std::string(R"({"dataset":"blobs_64x64x64_uint8","eps":)") + std::to_string(0.1 * i) + "}";
        const auto res = c->Post("/api/fit", body, "application/json");
        ASSERT_TRUE(res);
        if (res->status == 202) ++accepted;
        if (res->status == 429) {
            ++refused;
            EXPECT_TRUE(bodyJson(res).contains("error"));
        }
    }
    EXPECT_LE(accepted, 3);
    EXPECT_GE(refused, 3);
}

TEST(ServerCache, DiskCacheServesARestartedServer) {
    ServerWorld world;
    const std::string query = "/render?dataset=mri-brain_33x41x25_int16&size=64x64&eps=6%25";
    std::string first;
    {
        LoopbackServer server(world.options());
        const auto res = server.client()->Get(query.c_str());
        ASSERT_TRUE(res);
        ASSERT_EQ(res->status, 200) << res->body;
        first = res->body;
    }
    LoopbackServer server(world.options());
    auto c = server.client();
    const auto res = c->Get(query.c_str());
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200);
    EXPECT_EQ(res->body, first);
    const auto stats = bodyJson(c->Get("/api/stats"));
    ASSERT_EQ(stats["fits"].size(), 1u);
    EXPECT_EQ(stats["fits"][0]["source"], "disk");
}

TEST(ServerCache, UnwritableCacheFolderKeepsServing) {
    ServerWorld world;
    auto options = world.options();
    world.dir().write("not-a-folder", "x");
    options.cacheDir = world.dir().path() / "not-a-folder" / "cache"; // cannot be created
    options.withRenderer = false;
    LoopbackServer server(options);
    auto c = server.client();
    const auto post =
        c->Post("/api/fit", R"({"dataset":"mri-brain_33x41x25_int16","eps":"5%"})", "application/json");
    ASSERT_TRUE(post);
    ASSERT_EQ(post->status, 202);
    const auto stats = bodyJson(c->Get("/api/stats"));
    EXPECT_FALSE(stats["cache"]["diskEnabled"].get<bool>());
}

TEST(ServerNoRenderer, ApiWorksAndRenderIs503) {
    ServerWorld world;
    auto options = world.options();
    options.withRenderer = false;
    LoopbackServer server(options);
    auto c = server.client();
    const auto list = c->Get("/api/datasets");
    ASSERT_TRUE(list);
    EXPECT_EQ(list->status, 200);
    const auto res = c->Get("/render?dataset=blobs_64x64x64_uint8&size=32x32");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 503);
    EXPECT_EQ(bodyJson(res)["error"], "rendering is disabled");
}

} // namespace
} // namespace vots::test
