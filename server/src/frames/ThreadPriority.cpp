// Thread priorities through setpriority (nice) and sched_setscheduler (SCHED_IDLE), per thread on Linux.
#include "vots/server/ThreadPriority.h"

#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

namespace vots::server {

void lowerThisThreadToNice19() {
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);
}

void lowerThisThreadToIdle() {
    const sched_param idle{};
    sched_setscheduler(static_cast<pid_t>(gettid()), SCHED_IDLE, &idle);
}

} // namespace vots::server
