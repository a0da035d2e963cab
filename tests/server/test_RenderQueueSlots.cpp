// The render thread holds two Vot-Spaces uploaded: frames alternating between them (a viewer's drafts from
// the draft rung's fit, its still from the eps's own) upload neither again; a third replaces the one drawn
// least recently.
#include "RenderQueueJobs.h"
#include "ServerStats.h"
#include "frames/ForegroundActivity.h"
#include "frames/RenderQueue.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace vots::server {
namespace {

/// Whether a 32^2 frame of `space` uploaded it first; checks that it drew every Vot's space.
bool uploads(RenderQueue& queue, const std::shared_ptr<const fit::VotSpace>& space) {
    RenderJob job = test::frameOf("", 32);
    job.space = space;
    const RenderResult result = queue.render(std::move(job));
    EXPECT_EQ(result.votCount, space->vots.size());
    return result.uploadMs > 0.0;
}

TEST(RenderQueueSlots, TwoVotSpacesStayUploadedAndAThirdReplacesTheOneDrawnLeastRecently) {
    ServerStats stats;
    ForegroundActivity foreground;
    RenderQueue queue(stats, foreground);
    ASSERT_TRUE(queue.hasContext()) << queue.contextError();
    // Equal Vots in three copies: the render thread tells Vot-Spaces apart by identity, as the fit cache
    // hands them out.
    const auto a = test::blobSpace();
    const auto b = std::make_shared<const fit::VotSpace>(*a);
    const auto c = std::make_shared<const fit::VotSpace>(*a);

    EXPECT_TRUE(uploads(queue, a));
    EXPECT_TRUE(uploads(queue, b));
    for (int turn = 0; turn < 3; ++turn) {
        EXPECT_FALSE(uploads(queue, a)) << turn;
        EXPECT_FALSE(uploads(queue, b)) << turn;
    }
    // a was drawn before b: c takes a's place, and b stays.
    EXPECT_TRUE(uploads(queue, c));
    EXPECT_FALSE(uploads(queue, b));
    EXPECT_FALSE(uploads(queue, c));
    EXPECT_TRUE(uploads(queue, a));
}

TEST(RenderQueueSlots, TwoVotSpacesTooLargeTogetherAreNotHeldAtOnce) {
    ServerStats stats;
    ForegroundActivity foreground;
    const auto a = test::blobSpace();
    const auto b = std::make_shared<const fit::VotSpace>(*a);
    // Room for one and a half of them: the second lets the first go, and they upload in turn.
    RenderQueue queue(stats, foreground, nullptr, 64, a->vots.size() * 3 / 2);
    ASSERT_TRUE(queue.hasContext()) << queue.contextError();
    EXPECT_FALSE(queue.holdsBoth(a->vots.size(), b->vots.size()));
    for (int turn = 0; turn < 3; ++turn) {
        EXPECT_TRUE(uploads(queue, a)) << turn;
        EXPECT_FALSE(uploads(queue, a)) << turn;
        EXPECT_TRUE(uploads(queue, b)) << turn;
    }
}

} // namespace
} // namespace vots::server
