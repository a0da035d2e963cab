// Params: query splitting, defaults, and the 400s for malformed values (no server needed).
#include "HttpError.h"
#include "routes/Params.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vots::server {
namespace {

int statusOf(const QueryParams& query) {
    try {
        parseRenderParams(query);
    } catch (const HttpError& e) {
        return e.status();
    }
    return 200;
}

TEST(Params, QueryStringSplitsAtFirstEqualsAndDecodes) {
    const auto q = parseQueryString("dataset=a&cam=az=30,el=20&eps=2%&w=1%2C2&x=a+b&flag");
    EXPECT_EQ(q.find("cam")->second, "az=30,el=20");
    EXPECT_EQ(q.find("eps")->second, "2%");
    EXPECT_EQ(q.find("w")->second, "1,2");
    EXPECT_EQ(q.find("x")->second, "a b");
    EXPECT_EQ(q.find("flag")->second, "");
}

TEST(Params, TargetQueryIsWhatFollowsTheFirstQuestionMark) {
    const auto q = targetQueryParams("/render?dataset=a&cam=az=30?x");
    ASSERT_EQ(q.size(), 2u);
    EXPECT_EQ(q.find("dataset")->second, "a");
    EXPECT_EQ(q.find("cam")->second, "az=30?x");
    EXPECT_TRUE(targetQueryParams("/render").empty());
    EXPECT_TRUE(targetQueryParams("/render?").empty());
}

TEST(Params, DefaultsMatchTheContract) {
    const RenderParams p = parseRenderParams({{"dataset", "cranium"}});
    EXPECT_EQ(p.camera, render::cameraForView(render::ViewPreset::Anterior));
    EXPECT_EQ(p.width, 512);
    EXPECT_EQ(p.height, 512);
    EXPECT_TRUE(p.eps.isPercent);
    EXPECT_EQ(p.eps.value, 2.0);
    EXPECT_EQ(p.degree, 3);
    EXPECT_EQ(p.mode, render::RenderMode::Mip);
    EXPECT_EQ(p.renderer, render::RendererKind::Vots);
    EXPECT_FALSE(p.slab);
    EXPECT_FALSE(p.window);
    EXPECT_EQ(p.colormap, render::Colormap::Grey);
}

TEST(Params, ParsesEveryField) {
    const RenderParams p = parseRenderParams({{"dataset", "blobs_64x64x64_uint8"},
                                              {"cam", "az=30,el=20"},
                                              {"size", "128x64"},
                                              {"eps", "12.5"},
                                              {"degree", "1"},
                                              {"mode", "density"},
                                              {"window", "40,400"},
                                              {"colormap", "bone"},
                                              {"client", "tab-1"},
                                              {"_", "1699999999"}});
    EXPECT_EQ(p.camera.azimuthDeg, 30.0);
    EXPECT_EQ(p.width, 128);
    EXPECT_EQ(p.height, 64);
    EXPECT_FALSE(p.eps.isPercent);
    EXPECT_EQ(p.eps.value, 12.5);
    EXPECT_EQ(p.degree, 1);
    EXPECT_EQ(p.mode, render::RenderMode::Density);
    ASSERT_TRUE(p.window);
    EXPECT_EQ(p.window->level, 40.f);
    EXPECT_EQ(p.window->colormap, render::Colormap::Bone);
    EXPECT_EQ(p.client, "tab-1");
}

TEST(Params, ModeRendererAndSlab) {
    const RenderParams p = parseRenderParams(
        {{"dataset", "cranium"}, {"mode", "aip"}, {"renderer", "grid"}, {"slab", "-20.5,10"}});
    EXPECT_EQ(p.mode, render::RenderMode::Aip);
    EXPECT_EQ(p.renderer, render::RendererKind::Grid);
    ASSERT_TRUE(p.slab);
    EXPECT_EQ(*p.slab, (render::Slab{-20.5, 10}));
    // "reference" is mip on the grid, as before the grid drew every mode.
    const RenderParams reference = parseRenderParams({{"dataset", "cranium"}, {"mode", "reference"}});
    EXPECT_EQ(reference.mode, render::RenderMode::Mip);
    EXPECT_EQ(reference.renderer, render::RendererKind::Grid);
    EXPECT_EQ(parseRenderParams({{"dataset", "c"}, {"mode", "minip"}}).mode, render::RenderMode::MinIp);
}

TEST(Params, MalformedValuesAre400) {
    const std::vector<QueryParams> bad{
        {},
        {{"dataset", "../x"}},
        {{"dataset", "a"}, {"size", "0x0"}},
        {{"dataset", "a"}, {"size", "4097x1"}},
        {{"dataset", "a"}, {"size", "12"}},
        {{"dataset", "a"}, {"eps", "0"}},
        {{"dataset", "a"}, {"eps", "nan"}},
        {{"dataset", "a"}, {"eps", "inf%"}},
        {{"dataset", "a"}, {"eps", "0x10"}},
        {{"dataset", "a"}, {"cam", "az=nan"}},
        {{"dataset", "a"}, {"mode", "xray"}},
        {{"dataset", "a"}, {"renderer", "gpu"}},
        {{"dataset", "a"}, {"mode", "reference"}, {"renderer", "vots"}},
        {{"dataset", "a"}, {"mode", "density"}, {"renderer", "grid"}},
        {{"dataset", "a"}, {"slab", "10"}},
        {{"dataset", "a"}, {"slab", "0,0"}},
        {{"dataset", "a"}, {"slab", "0,-5"}},
        {{"dataset", "a"}, {"slab", "nan,5"}},
        {{"dataset", "a"}, {"slab", "0,1e999"}},
        {{"dataset", "a"}, {"colormap", "jet"}},
        {{"dataset", "a"}, {"window", "1"}},
        {{"dataset", "a"}, {"degree", "4"}},
        {{"dataset", "a"}, {"other", "1"}},
        {{"dataset", "a"}, {"dataset", "b"}},
        {{"dataset", "a"}, {"client", "a b"}},
        {{"dataset", "a"}, {"cam", std::string(600, 'x')}},
    };
    for (const auto& query : bad)
        EXPECT_EQ(statusOf(query), 400) << (query.empty() ? "" : query.rbegin()->second);
}

TEST(Params, EpsResolvesLikeTheCli) {
    EXPECT_FLOAT_EQ(parseEpsSpec("2%").resolve(0.f, 255.f), 5.1f);
    EXPECT_FLOAT_EQ(parseEpsSpec("7").resolve(0.f, 255.f), 7.f);
    EXPECT_EQ(parseEpsSpec("2%").resolve(3.f, 3.f), 0.f);
}

TEST(Params, FitBodyParsesAndRefusesBadFields) {
    const FitParams p = parseFitParams(
        R"({"dataset":"a","eps":"3%","degree":2,"focus":{"x":1,"y":2,"z":3,"r":4,"eps":0.5}})");
    EXPECT_EQ(p.dataset, "a");
    EXPECT_TRUE(p.eps.isPercent);
    EXPECT_EQ(p.degree, 2);
    ASSERT_TRUE(p.focus);
    EXPECT_EQ(p.focus->radius, 4.0);
    EXPECT_EQ(p.focus->epsFocus, 0.5f);
    EXPECT_EQ(p.client, "");
    EXPECT_EQ(parseFitParams(R"({"dataset":"a","client":"tab-1_x"})").client, "tab-1_x");
    for (const char* body :
         {"", "[]", "{\"eps\":1}", "{\"dataset\":\"a\",\"eps\":-1}", "{\"dataset\":\"a\",\"degree\":1.5}",
          "{\"dataset\":\"a\",\"focus\":{\"x\":1}}", "{\"dataset\":\"a\",\"extra\":1}",
          "{\"dataset\":\"a\",\"client\":7}", "{\"dataset\":\"a\",\"client\":\"\"}",
          "{\"dataset\":\"a\",\"client\":\"a/b\"}"}) {
        EXPECT_THROW(parseFitParams(body), HttpError) << body;
    }
}

} // namespace
} // namespace vots::server
