// ThreadPriority: each helper lowers the calling thread alone, not the thread that started it.
#include "vots/server/ThreadPriority.h"

#include <gtest/gtest.h>

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <thread>

namespace vots::server {
namespace {

int niceOfThisThread() {
    return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

TEST(ThreadPriority, IdleIsSchedIdleForTheCallingThreadOnly) {
    const int before = sched_getscheduler(0);
    int policy = -1;
    std::thread([&policy] {
        lowerThisThreadToIdle();
        policy = sched_getscheduler(0);
    }).join();
    EXPECT_EQ(policy, SCHED_IDLE);
    EXPECT_EQ(sched_getscheduler(0), before) << "the caller keeps its policy";
}

TEST(ThreadPriority, Nice19ForTheCallingThreadOnly) {
    const int before = niceOfThisThread();
    int nice = 0;
    std::thread([&nice] {
        lowerThisThreadToNice19();
        nice = niceOfThisThread();
    }).join();
    EXPECT_EQ(nice, 19);
    EXPECT_EQ(niceOfThisThread(), before) << "the caller keeps its priority";
}

} // namespace
} // namespace vots::server
