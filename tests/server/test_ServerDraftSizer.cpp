// The socket's drafts keep to their time budget, but the first draft of a Vot-Space the socket has not
// drawn (after a refit it waits for the upload) does not shrink the drafts after it.
#include "HoldingRanks.h"
#include "ServerFixture.h"
#include "WebSocketClient.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <memory>
#include <string>
#include <thread>

namespace vots::test {
namespace {

constexpr auto HELD = std::chrono::milliseconds(300); // far over the draft budget (DRAFT_BUDGET_MS)

class DraftSizerOverSocket : public ::testing::Test {
protected:
    DraftSizerOverSocket() : mRanks(std::make_shared<HoldingRanks>(false)) {
        auto options = mWorld.options();
        options.ranks = mRanks; // frames drawn flat and at once, or held as long as the test says
        options.warmUpFits = false;
        mServer = std::make_unique<LoopbackServer>(options);
        mSocket = std::make_unique<WebSocketClient>(mServer->port(), "/api/stream");
    }
    ~DraftSizerOverSocket() override { mRanks->release(); }

    /// Draws a draft of the view at eps (a new camera each time, so none is a repeat), held for HELD when
    /// `held`; acknowledges it and returns its width (0 when no frame came).
    int draft(const std::string& eps, bool held = false) {
        ++mSeq;
        if (held) mRanks->holdNext();
        const nlohmann::json view{
            {"type", "view"},
            {"seq", mSeq},
            {"still", false},
            {"params",
             {{"dataset", BLOBS}, {"cam", "az=" + std::to_string(mSeq)}, {"size", "96x64"}, {"eps", eps}}}};
        if (!mSocket->sendText(view.dump())) return 0;
        if (held) {
            if (!mRanks->waitUntilHolding()) return 0;
            std::this_thread::sleep_for(HELD);
            mRanks->release();
        }
        const auto header = mSocket->read();
        const auto image = mSocket->read();
        if (!header || !header->text || !image || image->text) return 0;
        const auto frame = nlohmann::json::parse(header->bytes);
        if (frame["type"] != "frame") return 0;
        mSocket->sendText(nlohmann::json{{"type", "ack"}, {"frame", frame["frame"]}}.dump());
        return frame["width"].get<int>();
    }

    ServerWorld mWorld;
    std::shared_ptr<HoldingRanks> mRanks;
    std::unique_ptr<LoopbackServer> mServer;
    std::unique_ptr<WebSocketClient> mSocket;
    std::uint64_t mSeq = 0;
};

TEST_F(DraftSizerOverSocket, TheFirstDraftOfANewVotSpaceDoesNotShrinkTheNext) {
    ASSERT_TRUE(mSocket->handshakeOk());
    ASSERT_GT(draft("5%"), 0);
    ASSERT_GT(draft("5%"), 0); // the sizer has timed quick drafts of this view
    // The first draft at a new eps, slow as a refit's upload makes it: not timed.
    const int atNewEps = draft("6%", true);
    ASSERT_GT(atNewEps, 0);
    const int after = draft("6%");
    EXPECT_EQ(after, atNewEps) << "the draft waiting for its Vot-Space shrank the next one";

    // A slow draft of a Vot-Space the socket has drawn is timed: the sizer still follows the load.
    ASSERT_GT(draft("6%", true), 0);
    const int afterSlow = draft("6%");
    EXPECT_GT(afterSlow, 0);
    EXPECT_LT(afterSlow, after) << "a draft over its budget did not shrink the next one";
}

} // namespace
} // namespace vots::test
