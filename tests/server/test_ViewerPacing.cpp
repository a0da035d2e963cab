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

std::optional<std::uint64_t> frame(std::uint64_t number) {
    return number;
}

TEST(ViewerPacing, TheLatestViewWinsAndOlderOnesAreDropped) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1));
    const auto first = pacing.next();
    ASSERT_TRUE(first);
    EXPECT_EQ(first->seq, 1u);
    for (std::uint64_t seq = 2; seq <= 9; ++seq)
        pacing.offer(viewNumber(seq));
    EXPECT_FALSE(pacing.next()) << "one draft at a time";
    EXPECT_EQ(pacing.sent(*first), frame(1));
    const auto second = pacing.next();
    ASSERT_TRUE(second);
    EXPECT_EQ(second->seq, 9u);
    EXPECT_EQ(pacing.dropped(), 7u);
    EXPECT_FALSE(pacing.next()) << "nothing new";
}

TEST(ViewerPacing, TheNextDraftStartsOnceTheLastIsRenderedWhileItIsEncoded) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1));
    const auto first = pacing.next();
    ASSERT_TRUE(first);
    pacing.offer(viewNumber(2));
    EXPECT_FALSE(pacing.next()) << "one draft rendered at a time";
    pacing.rendered(*first);
    const auto second = pacing.next();
    ASSERT_TRUE(second) << "the render thread goes on while the first is encoded";
    EXPECT_EQ(second->seq, 2u);
    EXPECT_EQ(pacing.inFlight(), 2u) << "one encoded, one rendered";
    pacing.offer(viewNumber(3));
    pacing.rendered(*second);
    EXPECT_FALSE(pacing.next()) << "two in flight, both still being encoded";
    EXPECT_EQ(pacing.sent(*first), frame(1));
    EXPECT_FALSE(pacing.next()) << "frame 1 is not acknowledged yet";
    EXPECT_TRUE(pacing.acknowledge(1));
    const auto third = pacing.next();
    ASSERT_TRUE(third);
    EXPECT_EQ(third->seq, 3u);
    // A rendered draft that fails in its encoding leaves the draft being rendered as it is.
    pacing.failed(*second);
    pacing.offer(viewNumber(4));
    EXPECT_FALSE(pacing.next()) << "the third is still rendered";
    EXPECT_EQ(pacing.sent(*third), frame(2));
    EXPECT_EQ(pacing.inFlight(), 1u) << "frame 2, until acknowledged";
    const auto fourth = pacing.next();
    ASSERT_TRUE(fourth);
    EXPECT_EQ(fourth->seq, 4u);
}

TEST(ViewerPacing, APageRepeatingItsSequenceNumbersCannotWedgeThePacing) {
    // A broken or hostile page may send the same seq twice: whatever the order the drafts end in, the
    // places they held come back.
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(5));
    const auto first = pacing.next();
    ASSERT_TRUE(first);
    pacing.rendered(*first);
    pacing.offer(viewNumber(5));
    const auto second = pacing.next();
    ASSERT_TRUE(second);
    EXPECT_TRUE(pacing.sent(*first));
    pacing.rendered(*second);
    pacing.failed(*second);
    EXPECT_TRUE(pacing.acknowledge(1));
    EXPECT_EQ(pacing.inFlight(), 0u);
    pacing.offer(viewNumber(6));
    EXPECT_TRUE(pacing.next()) << "a draft can be taken again";
}

TEST(ViewerPacing, NoMoreInFlightThanAcknowledged) {
    ViewerPacing pacing(2);
    for (std::uint64_t seq = 1; seq <= 2; ++seq) {
        pacing.offer(viewNumber(seq));
        const auto taken = pacing.next();
        ASSERT_TRUE(taken);
        EXPECT_EQ(pacing.sent(*taken), frame(seq));
    }
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
    pacing.failed(*third);
    EXPECT_EQ(pacing.inFlight(), 1u);
}

TEST(ViewerPacing, AStillDoesNotWaitForAcknowledgements) {
    ViewerPacing pacing(2);
    for (std::uint64_t seq = 1; seq <= 2; ++seq) {
        pacing.offer(viewNumber(seq));
        const auto taken = pacing.next();
        ASSERT_TRUE(taken);
        pacing.sent(*taken);
    }
    pacing.offer(viewNumber(3));
    EXPECT_FALSE(pacing.next()) << "a draft waits for an ack";
    pacing.offer(viewNumber(4, true));
    const auto still = pacing.next();
    ASSERT_TRUE(still);
    EXPECT_EQ(still->seq, 4u);
    EXPECT_TRUE(still->still);
    pacing.offer(viewNumber(5, true));
    const auto newerStill = pacing.next();
    ASSERT_TRUE(newerStill) << "a newer still does not wait behind an older one";
    EXPECT_TRUE(pacing.overtaken(*still));
    pacing.offer(viewNumber(6, true));
    EXPECT_FALSE(pacing.next()) << "two stills at a time at most";
    EXPECT_EQ(pacing.sent(*newerStill), frame(3));
    pacing.failed(*still); // superseded on the render queue
    const auto third = pacing.next();
    ASSERT_TRUE(third);
    EXPECT_EQ(third->seq, 6u);
}

TEST(ViewerPacing, AStillDoesNotWaitBehindADraftWhoseFrameIsThenDropped) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1));
    const auto draft = pacing.next();
    ASSERT_TRUE(draft);
    EXPECT_FALSE(pacing.overtaken(*draft));
    pacing.offer(viewNumber(2, true));
    const auto still = pacing.next();
    ASSERT_TRUE(still) << "the still starts while the draft is drawn";
    EXPECT_TRUE(pacing.overtaken(*draft)) << "the draft shows a camera the page has left";
    EXPECT_FALSE(pacing.overtaken(*still));
    EXPECT_EQ(pacing.sent(*still), frame(1));
    EXPECT_EQ(pacing.sent(*draft), std::nullopt) << "older than a frame sent: dropped, not sent";
    EXPECT_EQ(pacing.dropped(), 1u);
    EXPECT_EQ(pacing.inFlight(), 1u) << "the still, until acknowledged";
}

TEST(ViewerPacing, ADraftMayStartWhileAnOlderStillIsDrawn) {
    ViewerPacing pacing(2);
    pacing.offer(viewNumber(1, true));
    const auto still = pacing.next();
    ASSERT_TRUE(still);
    pacing.offer(viewNumber(2));
    const auto draft = pacing.next();
    ASSERT_TRUE(draft) << "the drag goes on: the draft queues behind the still";
    EXPECT_TRUE(pacing.overtaken(*still));
    pacing.offer(viewNumber(3));
    EXPECT_FALSE(pacing.next()) << "one draft at a time";
    EXPECT_EQ(pacing.sent(*draft), frame(1));
    EXPECT_EQ(pacing.sent(*still), std::nullopt);
    const auto third = pacing.next();
    ASSERT_TRUE(third);
    EXPECT_EQ(third->seq, 3u);
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

TEST(DraftSizer, DraftsComeFromTheRungWhereDraftsAtEpsWouldBeSmallerThanTheFrame) {
    constexpr double BUDGET = 30;
    constexpr int W = 1000, H = 800;
    DraftSizer atEps(BUDGET), atRung(BUDGET);
    // Nothing measured: from the rung, whose drafts are then measured.
    EXPECT_TRUE(draftFromRung(atEps, atRung, W, H));
    // A CPU: the rung's full-size draft would take 60 ms, at eps more: from the rung.
    atRung.observe(W / 2, H / 2, 15);
    EXPECT_TRUE(draftFromRung(atEps, atRung, W, H));
    // A GPU: the rung's full-size draft takes 4 ms, under a RUNG_GAIN-th of the budget: a try at eps.
    DraftSizer fastRung(BUDGET);
    fastRung.observe(W, H, 4);
    EXPECT_FALSE(draftFromRung(atEps, fastRung, W, H));
    // At eps full size within the budget: at eps; over it (a heavier view): back to the rung.
    atEps.observe(W, H, 12);
    EXPECT_FALSE(draftFromRung(atEps, fastRung, W, H));
    EXPECT_TRUE(atEps.fullSizeWithin(W, H));
    for (int i = 0; i < 10; ++i)
        atEps.observe(W, H, 45);
    EXPECT_FALSE(atEps.fullSizeWithin(W, H));
    EXPECT_TRUE(draftFromRung(atEps, fastRung, W, H));
}

} // namespace
} // namespace vots::server
