// LowPriorityQueue: tasks run in order on one thread, drain waits for them, a full queue refuses, and
// the destructor runs what is still pending.
#include "fits/LowPriorityQueue.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

namespace vots::server {
namespace {

TEST(LowPriorityQueue, RunsTasksInOrderAtNiceNineteen) {
    // The suite may itself run under nice: the caller must keep whatever priority it started with.
    const int callerNice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
    LowPriorityQueue queue(16);
    std::vector<int> order; // written by the worker only, read after drain()
    int nice = 0;
    for (int i = 0; i < 10; ++i)
        ASSERT_TRUE(queue.post([&order, i] { order.push_back(i); }));
    ASSERT_TRUE(queue.post([&nice] { nice = getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())); }));
    queue.drain();
    EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
    EXPECT_EQ(nice, 19);
    EXPECT_EQ(getpriority(PRIO_PROCESS, static_cast<id_t>(gettid())), callerNice)
        << "the caller keeps its priority";
}

TEST(LowPriorityQueue, RefusesBeyondItsLimitAndFinishesPendingTasksWhenDestroyed) {
    std::atomic<int> ran{0};
    std::promise<void> release;
    std::shared_future<void> released = release.get_future().share();
    {
        LowPriorityQueue queue(2);
        std::promise<void> started;
        ASSERT_TRUE(queue.post([&started, released, &ran] {
            started.set_value();
            released.wait();
            ++ran;
        }));
        started.get_future().wait(); // the first task runs, so two more fit in the queue
        EXPECT_TRUE(queue.post([&ran] { ++ran; }));
        EXPECT_TRUE(queue.post([&ran] { ++ran; }));
        EXPECT_FALSE(queue.post([&ran] { ran += 100; }));
        release.set_value();
    }
    EXPECT_EQ(ran.load(), 3);
}

} // namespace
} // namespace vots::server
