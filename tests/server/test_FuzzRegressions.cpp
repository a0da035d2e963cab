// Replays the fuzz seeds and crashes of fuzz_camera, fuzz_render_query and fuzz_stream_message: each parses
// or is refused cleanly.
#include "FuzzCorpus.h"

#include "HttpError.h"
#include "routes/Params.h"
#include "stream/StreamMessages.h"
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

TEST(FuzzRegressions, StreamMessage) {
    const auto inputs = fuzzInputs("fuzz_stream_message");
    ASSERT_FALSE(inputs.empty());
    int views = 0, acks = 0, closes = 0, refusals = 0;
    for (const auto& [name, text] : inputs) {
        SCOPED_TRACE(name);
        try {
            const auto message = vots::server::parseClientMessage(text);
            if (const auto* view = std::get_if<vots::server::ViewMessage>(&message)) {
                ++views;
                EXPECT_TRUE(
                    vots::server::isDatasetName(vots::server::parseRenderParams(view->query).dataset));
            } else {
                ++acks;
            }
        } catch (const vots::server::ProtocolError& e) {
            ++closes;
            EXPECT_TRUE(e.code() == vots::server::CloseCode::InvalidPayload ||
                        e.code() == vots::server::CloseCode::Policy);
        } catch (const vots::server::HttpError& e) {
            ++refusals;
            EXPECT_EQ(e.status(), 400);
        }
    }
    // The seeds cover every outcome.
    EXPECT_GT(views, 0);
    EXPECT_GT(acks, 0);
    EXPECT_GT(closes, 0);
    EXPECT_GT(refusals, 0);
}

} // namespace
