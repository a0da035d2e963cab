// Replays the fuzz seeds and crashes of fuzz_camera and fuzz_render_query: each parses or is refused cleanly.
#include "FuzzCorpus.h"

#include "HttpError.h"
#include "routes/Params.h"
#include "vots/fit/Error.h"
#include "vots/render/CameraText.h"

#include <gtest/gtest.h>

namespace {

using vots::test::fuzzInputs;

TEST(FuzzRegressions, Camera) {
    const auto inputs = fuzzInputs("fuzz_camera");
    ASSERT_FALSE(inputs.empty());
    for (const auto& [name, text] : inputs) {
        SCOPED_TRACE(name);
        try {
            const auto camera = vots::render::parseCamera(text);
            const auto again = vots::render::parseCamera(vots::render::formatCamera(camera));
            EXPECT_EQ(vots::render::formatCamera(again), vots::render::formatCamera(camera));
        } catch (const vots::fit::InputError&) {
        }
    }
}

TEST(FuzzRegressions, RenderQueryAndFitBody) {
    const auto inputs = fuzzInputs("fuzz_render_query");
    ASSERT_FALSE(inputs.empty());
    for (const auto& [name, text] : inputs) {
        SCOPED_TRACE(name);
        try {
            const auto params = vots::server::parseRenderParams(vots::server::parseQueryString(text));
            EXPECT_TRUE(vots::server::isDatasetName(params.dataset));
        } catch (const vots::server::HttpError& e) {
            EXPECT_EQ(e.status(), 400);
        }
        try {
            (void)vots::server::parseFitParams(text);
        } catch (const vots::server::HttpError& e) {
            EXPECT_EQ(e.status(), 400);
        }
    }
}

} // namespace
