// A viewer's drafts come from the fit at its eps's draft rung once the server holds it, and never wait for
// it; the still after the drag is drawn at the eps itself, the same PNG as /render.
#include "ServerFixture.h"
#include "WebSocketClient.h"

#include "vots/render/Jpeg.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace vots::test {
namespace {

class ServerDraftRung : public ::testing::Test {
protected:
    ServerDraftRung() {
        auto options = mWorld.options();
        options.warmUpFits = false; // the draft rung is fitted when the test asks
        mServer = std::make_unique<LoopbackServer>(options);
        mSocket = std::make_unique<WebSocketClient>(mServer->port(), "/api/stream");
    }

    /// Sends a view at a camera not drawn before, reads its frame and acknowledges it; its header and image.
    std::pair<nlohmann::json, std::string> frame(bool still, const std::string& mode = "mip") {
        ++mSeq;
        nlohmann::json view{
            {"type", "view"},
            {"seq", mSeq},
            {"still", still},
            {"params", {{"dataset", BLOBS}, {"cam", "az=" + std::to_string(10 * mSeq)}, {"size", "96x64"}}}};
        if (mEps) view["params"]["eps"] = nlohmann::json(*mEps).dump();
        view["params"]["mode"] = mode;
        EXPECT_TRUE(mSocket->sendText(view.dump()));
        const auto header = mSocket->read();
        const auto image = mSocket->read();
        if (!header || !header->text || !image || image->text) {
            ADD_FAILURE() << "no frame; close code " << mSocket->closeCode();
            return {};
        }
        auto json = nlohmann::json::parse(header->bytes);
        EXPECT_EQ(json["type"], "frame") << header->bytes;
        mSocket->sendText(nlohmann::json{{"type", "ack"}, {"frame", json["frame"]}}.dump());
        return {json, image->bytes};
    }

    /// The Vot count of the fit at `eps`, fitted now if need be.
    std::size_t votsAt(double eps) {
        auto c = mServer->client();
        const auto posted = bodyJson(
            c->Post("/api/fit", nlohmann::json{{"dataset", BLOBS}, {"eps", eps}}.dump(), "application/json"));
        const auto job = waitForJob(*c, posted);
        EXPECT_EQ(job["state"], "done") << job.dump();
        return job["votCount"].get<std::size_t>();
    }

    ServerWorld mWorld;
    std::unique_ptr<LoopbackServer> mServer;
    std::unique_ptr<WebSocketClient> mSocket;
    std::uint64_t mSeq = 0;
    std::optional<double> mEps; // the views' eps in data units; none: the dataset's default
};

TEST_F(ServerDraftRung, DraftsComeFromTheDraftRungOnceItIsFittedAndTheStillFromTheEpsItself) {
    ASSERT_TRUE(mSocket->handshakeOk());
    auto c = mServer->client();
    nlohmann::json blobs;
    const nlohmann::json list = bodyJson(c->Get("/api/datasets")); // kept: the loop reads into it
    for (const auto& d : list["datasets"])
        if (d["name"] == BLOBS) blobs = d;
    ASSERT_FALSE(blobs.is_null());
    const double eps = blobs["defaultEps"].get<double>();
    const double span = blobs["range"][1].get<double>() - blobs["range"][0].get<double>();
    const auto steps = blobs["epsSteps"].get<std::vector<double>>();
    // The rule, recomputed: the slider's step nearest 4 x eps, at most a tenth of the range.
    const auto rungOf = [&](double at) {
        std::optional<double> nearest;
        for (const double step : steps)
            if (step <= 0.1 * span * 1.005 &&
                (!nearest || std::abs(std::log(step / (4 * at))) < std::abs(std::log(*nearest / (4 * at)))))
                nearest = step;
        return nearest;
    };
    const std::optional<double> rung = rungOf(eps);
    ASSERT_TRUE(rung && *rung > 3 * eps) << "blobs' default eps leaves no draft rung";
    const std::size_t fine = votsAt(eps);

    // No fit at the rung yet: the draft is drawn at eps, at once.
    const auto before = frame(false);
    EXPECT_EQ(before.first["format"], "image/jpeg");
    EXPECT_FALSE(before.first.contains("draftEps")) << before.first.dump();
    EXPECT_EQ(before.first["votCount"], fine);

    const std::size_t coarse = votsAt(*rung);
    ASSERT_LT(coarse, fine) << "the draft rung's fit is not coarser";
    const auto draft = frame(false);
    EXPECT_EQ(draft.first["format"], "image/jpeg");
    EXPECT_FLOAT_EQ(draft.first.value("draftEps", 0.f), static_cast<float>(*rung)) << draft.first.dump();
    EXPECT_EQ(draft.first["votCount"], coarse);
    const render::RgbaImage decoded = render::decodeJpeg({draft.second.begin(), draft.second.end()});
    EXPECT_EQ(decoded.width, draft.first["width"].get<int>());
    // Density draws the Vots' own sizes: the rung's would be another picture, so its drafts stay at eps.
    frame(false, "density");
    const auto density = frame(false, "density");
    EXPECT_FALSE(density.first.contains("draftEps")) << density.first.dump();
    EXPECT_EQ(density.first["votCount"], fine);

    // The still is the eps's own: /render's PNG byte for byte.
    const auto still = frame(true);
    EXPECT_EQ(still.first["format"], "image/png");
    EXPECT_FALSE(still.first.contains("draftEps"));
    EXPECT_EQ(still.first["votCount"], fine);
    const std::string cam = "az=" + std::to_string(10 * mSeq);
    const auto png =
        c->Get(("/render?dataset=" + std::string(BLOBS) + "&cam=" + cam + "&size=96x64").c_str());
    ASSERT_TRUE(png);
    ASSERT_EQ(png->status, 200) << png->body;
    EXPECT_TRUE(still.second == png->body) << "the still differs from /render's PNG";

    // A slider move down to a step whose draft rung is the default eps, held: the first frame at the new
    // eps (the viewer asks for a draft first) shows the new eps's own fit; the drag's drafts then come
    // from the default's.
    const auto lower = std::find_if(steps.begin(), steps.end(),
                                    [&](double step) { return rungOf(step) == std::optional<double>(eps); });
    ASSERT_NE(lower, steps.end());
    const std::size_t finer = votsAt(*lower);
    mEps = *lower;
    const auto moved = frame(false);
    EXPECT_FALSE(moved.first.contains("draftEps")) << moved.first.dump();
    EXPECT_EQ(moved.first["votCount"], finer);
    const auto dragged = frame(false);
    EXPECT_FLOAT_EQ(dragged.first.value("draftEps", 0.f), static_cast<float>(eps)) << dragged.first.dump();
    EXPECT_EQ(dragged.first["votCount"], fine);
}

} // namespace
} // namespace vots::test
