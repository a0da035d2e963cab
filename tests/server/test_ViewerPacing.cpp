// The viewer socket's parts without sockets: the message parser, latest-view-wins pacing by
// acknowledgements, and the draft size held to a frame-time budget.
#include "HttpError.h"
#include "stream/DraftSizer.h"
#include "stream/StreamMessages.h"
#include "stream/ViewerPacing.h"

#include <gtest/gtest.h>

namespace vots::server {
namespace {

PendingView viewNumber(std::uint64_t seq, bool still = false) {
    PendingView view;
    view.seq = seq;
    view.still = still;
    return view;
}

TEST(ViewerPacing, TheLatestViewWinsAndOlderOnesAreDropped) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1));
    const auto first = pacing.next();
    ASSERT_TRUE(first);
    EXPECT_EQ(first->seq, 1u);
    for (std::uint64_t seq = 2; seq <= 9; ++seq)
        pacing.offer(viewNumber(seq));
    EXPECT_FALSE(pacing.next()) << "one draw at a time";
    EXPECT_EQ(pacing.sent(), 1u);
    const auto second = pacing.next();
    ASSERT_TRUE(second);
    EXPECT_EQ(second->seq, 9u);
    EXPECT_EQ(pacing.dropped(), 7u);
    EXPECT_FALSE(pacing.next()) << "nothing new";
}

TEST(ViewerPacing, NoMoreInFlightThanAcknowledged) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1));
    ASSERT_TRUE(pacing.next());
    EXPECT_EQ(pacing.sent(), 1u);
    pacing.offer(viewNumber(2));
    ASSERT_TRUE(pacing.next());
    EXPECT_EQ(pacing.sent(), 2u);
    pacing.offer(viewNumber(3));
    EXPECT_EQ(pacing.inFlight(), 2u);
    EXPECT_FALSE(pacing.next()) << "two frames unacknowledged";
    EXPECT_TRUE(pacing.acknowledge(1));
    const auto third = pacing.next();
    ASSERT_TRUE(third);
    EXPECT_EQ(third->seq, 3u);
    EXPECT_EQ(pacing.inFlight(), 2u);
    EXPECT_FALSE(pacing.acknowledge(5)) << "frame 5 was never sent";
    EXPECT_TRUE(pacing.acknowledge(1)) << "an old ack is harmless";
    pacing.failed();
    EXPECT_EQ(pacing.inFlight(), 1u);
}

TEST(ViewerPacing, AStillDoesNotWaitForAcknowledgements) {
    ViewerPacing pacing(2);
    for (std::uint64_t seq = 1; seq <= 2; ++seq) {
        pacing.offer(viewNumber(seq));
        ASSERT_TRUE(pacing.next());
        pacing.sent();
    }
    pacing.offer(viewNumber(3));
    EXPECT_FALSE(pacing.next()) << "a draft waits for an ack";
    pacing.offer(viewNumber(4, true));
    const auto still = pacing.next();
    ASSERT_TRUE(still);
    EXPECT_EQ(still->seq, 4u);
    EXPECT_TRUE(still->still);
    pacing.offer(viewNumber(5, true));
    EXPECT_FALSE(pacing.next()) << "still one draw at a time";
}

TEST(DraftSizer, HoldsTheBudgetWithinItsScaleLimits) {
    DraftSizer sizer(30.0);
    EXPECT_EQ(sizer.draftSize(1000, 800), std::make_pair(500, 400)) << "half before any measurement";
    sizer.observe(500, 400, 60.0); // twice the budget: a quarter of the pixels next, half the side
    const auto [w, h] = sizer.draftSize(1000, 800);
    EXPECT_NEAR(w, 354, 2);
    EXPECT_NEAR(h, 283, 2);
    for (int i = 0; i < 20; ++i)
        sizer.observe(100, 100, 1000.0); // hopelessly slow: never below the minimum scale
    EXPECT_EQ(sizer.draftSize(1000, 800), std::make_pair(250, 200));
    for (int i = 0; i < 20; ++i)
        sizer.observe(1000, 800, 1.0); // fast: full size, never more
    EXPECT_EQ(sizer.draftSize(1000, 800), std::make_pair(1000, 800));
    sizer.observe(0, 0, 5.0); // nothing to learn from
    EXPECT_EQ(sizer.draftSize(1000, 800), std::make_pair(1000, 800));
}

TEST(StreamMessages, ParsesViewsAndAcks) {
    const ClientMessage view = parseClientMessage(
        R"({"type":"view","seq":7,"still":true,"params":{"dataset":"blobs","cam":"az=30"},"future":1})");
    const auto* v = std::get_if<ViewMessage>(&view);
    ASSERT_TRUE(v);
    EXPECT_EQ(v->seq, 7u);
    EXPECT_TRUE(v->still);
    EXPECT_EQ(v->query.find("cam")->second, "az=30");
    const ClientMessage ack = parseClientMessage(R"({"type":"ack","frame":3})");
    ASSERT_TRUE(std::get_if<AckMessage>(&ack));
    EXPECT_EQ(std::get<AckMessage>(ack).frame, 3u);
}

TEST(StreamMessages, BrokenMessagesNameTheirCloseCode) {
    const auto codeOf = [](const std::string& text) {
        try {
            parseClientMessage(text);
        } catch (const ProtocolError& e) {
            return e.code();
        }
        return CloseCode::Normal;
    };
    EXPECT_EQ(codeOf("{not json"), CloseCode::InvalidPayload);
    EXPECT_EQ(codeOf(""), CloseCode::InvalidPayload);
    for (const char* text : {"[]", "42", R"({"seq":1})", R"({"type":"dance"})",
                             R"({"type":"view","params":{}})", R"({"type":"view","seq":-1,"params":{}})",
                             R"({"type":"view","seq":1})", R"({"type":"view","seq":1,"params":{"size":640}})",
                             R"({"type":"view","seq":1,"still":"yes","params":{}})", R"({"type":"ack"})",
                             R"({"type":"ack","frame":1.5})"})
        EXPECT_EQ(codeOf(text), CloseCode::Policy) << text;
}

TEST(StreamMessages, BadRenderParametersAreTheRouteS400) {
    const auto view = std::get<ViewMessage>(
        parseClientMessage(R"({"type":"view","seq":1,"params":{"dataset":"blobs","size":"0x0"}})"));
    try {
        parseRenderParams(view.query);
        ADD_FAILURE() << "size 0x0 accepted";
    } catch (const HttpError& e) {
        EXPECT_EQ(e.status(), 400);
        EXPECT_NE(std::string(e.what()).find("size"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace vots::server
