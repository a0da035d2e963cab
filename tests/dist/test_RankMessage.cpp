// Messages between ranks: read back as sent, and refused when their version, kind or size is not this
// build's; failures keep their kind across ranks and end `vots` with one exit code per kind.
#include "vots/dist/Failure.h"
#include "vots/dist/RankMessage.h"
#include "vots/dist/WholeFill.h"

#include "vots/fit/Error.h"

#include <gtest/gtest.h>

#include <new>

namespace vots::test {
namespace {

struct Body {
    std::int32_t a = 0;
    double b = 0.0;
};

TEST(RankMessage, ABodyAndTailComeBackAsSent) {
    const std::string tail = "/data/volume.nrrd";
    const std::vector<char> message = dist::messageOf(7, Body{3, 2.5}, tail.data(), tail.size());
    const Body body = dist::bodyOf<Body>(message, 7);
    EXPECT_EQ(body.a, 3);
    EXPECT_EQ(body.b, 2.5);
    EXPECT_EQ(dist::tailOf(message), tail);
}

TEST(RankMessage, AnotherVersionKindOrSizeIsRefused) {
    std::vector<char> message = dist::messageOf(7, Body{3, 2.5});
    EXPECT_THROW(dist::bodyOf<Body>(message, 8), dist::BadRankMessage) << "another kind";
    EXPECT_THROW(dist::bodyOf<std::int32_t>(message, 7), dist::BadRankMessage) << "another body";
    std::vector<char> longer = message;
    longer.push_back('x');
    EXPECT_THROW(dist::headOf(longer), dist::BadRankMessage) << "a byte its head does not count";
    std::vector<char> shorter(message.begin(), message.end() - 1);
    EXPECT_THROW(dist::headOf(shorter), dist::BadRankMessage);
    EXPECT_THROW(dist::headOf(std::vector<char>(3)), dist::BadRankMessage) << "shorter than a head";
    dist::MessageHead head;
    std::memcpy(&head, message.data(), sizeof head);
    head.version = dist::RANK_PROTOCOL_VERSION + 1;
    std::memcpy(message.data(), &head, sizeof head);
    EXPECT_THROW(dist::headOf(message), dist::BadRankMessage) << "another version";
}

TEST(RankMessage, AFramesPixelsMustBeTheSizeItsBodySays) {
    const std::vector<float> pixels{1.f, 2.f, 3.f};
    const auto message = dist::messageOf(1, Body{}, pixels.data(), pixels.size() * sizeof(float));
    EXPECT_EQ(dist::floatTailOf(message, 3), pixels);
    EXPECT_THROW(dist::floatTailOf(message, 4), dist::BadRankMessage);
}

std::exception_ptr caught(const std::function<void()>& throwing) {
    try {
        throwing();
    } catch (...) {
        return std::current_exception();
    }
    return nullptr;
}

TEST(Failure, EachKindHasOneExitCodeAndCrossesRanksAsItself) {
    const auto input = caught([] { throw fit::InputError("bad eps"); });
    const auto budget = caught([] { throw dist::RanksOverBudget("too big"); });
    const auto memory = caught([] { throw std::bad_alloc(); });
    const auto other = caught([] { throw std::runtime_error("disk"); });
    EXPECT_EQ(dist::failureKindOf(input), dist::FailureKind::BadInput);
    EXPECT_EQ(dist::failureKindOf(budget), dist::FailureKind::OverBudget);
    EXPECT_EQ(dist::failureKindOf(memory), dist::FailureKind::Internal);
    EXPECT_EQ(dist::failureKindOf(other), dist::FailureKind::Internal);
    EXPECT_EQ(dist::failureTextOf(memory), "out of memory");
    EXPECT_EQ(dist::exitCodeOf(dist::FailureKind::BadInput), dist::EXIT_BAD_INPUT);
    EXPECT_EQ(dist::exitCodeOf(dist::FailureKind::Internal), dist::EXIT_FAILED);
    for (const auto& failure : {input, budget, other}) {
        const auto kind = dist::failureKindOf(failure);
        const auto again =
            dist::failureOf(dist::failureKindFromWire(static_cast<std::int32_t>(kind)), "rank 1: x");
        EXPECT_EQ(dist::failureKindOf(again), kind);
        EXPECT_EQ(dist::failureTextOf(again), "rank 1: x");
    }
    EXPECT_EQ(dist::failureKindFromWire(99), dist::FailureKind::Internal);
}

TEST(WholeFill, IsTheMeanOverEveryRanksBackgroundCells) {
    // 3 cells of -3000 on one rank, 1 of -2980 on the other: the whole's mean, not either rank's.
    EXPECT_EQ(dist::wholeVolumeFill({{3, -9000.0}, {1, -2980.0}}), std::optional<float>(-2995.f));
    EXPECT_EQ(dist::wholeVolumeFill({{0, 0.0}, {0, 0.0}}), std::nullopt);
}

} // namespace
} // namespace vots::test
