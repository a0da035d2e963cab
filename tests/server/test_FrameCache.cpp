// FrameCache: frames answered again, renders in flight shared, failures not kept, LRU over the budget.
#include "frames/FrameCache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

using vots::server::FrameCache;

namespace {

FrameCache::Frame frameOf(std::string png) {
    return FrameCache::Frame{std::move(png), 7, 1.5};
}

} // namespace

TEST(FrameCache, KeepsAFrameAndAnswersItAgain) {
    FrameCache cache(1 << 20);
    int renders = 0;
    auto render = [&] { return ++renders, frameOf("png-a"); };
    FrameCache::Source source{};
    EXPECT_EQ(cache.get("a", render, &source)->png, "png-a");
    EXPECT_EQ(source, FrameCache::Source::Rendered);
    const auto again = cache.get("a", render, &source);
    EXPECT_EQ(source, FrameCache::Source::Cached);
    EXPECT_EQ(again->png, "png-a");
    EXPECT_EQ(again->votCount, 7u);
    EXPECT_EQ(renders, 1);
    cache.get(
        "b", [] { return frameOf("png-b"); }, &source);
    EXPECT_EQ(source, FrameCache::Source::Rendered);
    const auto s = cache.summary();
    EXPECT_EQ(s.entries, 2u);
    EXPECT_EQ(s.rendered, 2u);
    EXPECT_EQ(s.cached, 1u);
}

TEST(FrameCache, IdenticalRequestsInFlightShareOneRender) {
    FrameCache cache(0); // nothing kept: every answer but the first must come from sharing
    std::mutex m;
    std::condition_variable cv;
    bool release = false;
    std::atomic<int> renders{0};
    auto slowRender = [&] {
        ++renders;
        std::unique_lock lock(m);
        cv.wait(lock, [&] { return release; });
        return frameOf("shared-png");
    };
    std::vector<std::future<std::pair<std::string, FrameCache::Source>>> waiters;
    for (int i = 0; i < 4; ++i)
        waiters.push_back(std::async(std::launch::async, [&] {
            FrameCache::Source source{};
            const auto frame = cache.get("k", slowRender, &source);
            return std::make_pair(frame->png, source);
        }));
    // Let every waiter reach the cache before the one render finishes.
    while (renders.load() == 0)
        std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    {
        std::lock_guard lock(m);
        release = true;
    }
    cv.notify_all();
    int rendered = 0, shared = 0;
    for (auto& w : waiters) {
        const auto [png, source] = w.get();
        EXPECT_EQ(png, "shared-png");
        rendered += source == FrameCache::Source::Rendered;
        shared += source == FrameCache::Source::Shared;
    }
    EXPECT_EQ(renders.load(), 1);
    EXPECT_EQ(rendered, 1);
    EXPECT_EQ(shared, 3);
    EXPECT_EQ(cache.summary().entries, 0u);
}

TEST(FrameCache, AFailedRenderIsNotInheritedByThoseWhoJoinedIt) {
    FrameCache cache(1 << 20);
    std::atomic<bool> started{false}, waiting{false};
    auto failing = [&]() -> FrameCache::Frame {
        started = true; // render() runs after its key is registered as in flight
        while (!waiting.load())
            std::this_thread::yield();
        std::this_thread::sleep_for(std::chrono::milliseconds(100)); // the joiner is waiting now
        throw std::runtime_error("superseded");
    };
    auto first = std::async(std::launch::async, [&] { return cache.get("k", failing); });
    while (!started.load())
        std::this_thread::yield();
    int joinerRenders = 0;
    auto second = std::async(std::launch::async, [&] {
        waiting = true;
        FrameCache::Source source{};
        const auto frame = cache.get(
            "k", [&] { return ++joinerRenders, frameOf("own"); }, &source);
        return std::make_pair(frame->png, source);
    });
    EXPECT_THROW(first.get(), std::runtime_error);
    const auto [png, source] = second.get();
    EXPECT_EQ(png, "own");
    EXPECT_EQ(source, FrameCache::Source::Rendered);
    EXPECT_EQ(joinerRenders, 1);
    EXPECT_EQ(cache.summary().entries, 1u); // the failure was not kept; the retry was
}

TEST(FrameCache, DropsTheLeastRecentlyUsedOverBudget) {
    const std::string big(400, 'x');
    FrameCache cache(1000); // two 400-byte frames (plus keys) fit, three do not
    FrameCache::Source source{};
    cache.get("a", [&] { return frameOf(big); });
    cache.get("b", [&] { return frameOf(big); });
    cache.get(
        "a", [&] { return frameOf(big); }, &source); // a is now the most recent
    EXPECT_EQ(source, FrameCache::Source::Cached);
    cache.get("c", [&] { return frameOf(big); });
    cache.get(
        "b", [&] { return frameOf(big); }, &source);
    EXPECT_EQ(source, FrameCache::Source::Rendered); // b was dropped
    cache.get(
        "a", [&] { return frameOf(big); }, &source);
    EXPECT_EQ(source, FrameCache::Source::Rendered); // then a, to make room for b
    EXPECT_LE(cache.summary().bytes, 1000u);
    cache.get(
        "huge", [] { return frameOf(std::string(5000, 'y')); }, &source);
    EXPECT_EQ(cache.summary().bytes <= 1000u, true); // larger than the budget: answered, not kept
}
