// Lowering the calling thread's CPU priority, for work nobody waits for (cache files, warm-ups, skip boxes).
#pragma once

namespace vots::server {

/// Nice 19 for the calling thread alone (Linux), inherited by threads it starts. It still progresses
/// on a busy machine. Failure only means normal priority.
void lowerThisThreadToNice19();

/// SCHED_IDLE for the calling thread alone (Linux), inherited by threads it starts: it runs only when
/// a core has nothing else to do, so it can wait for minutes on a busy machine. Failure only means
/// normal priority.
void lowerThisThreadToIdle();

} // namespace vots::server
