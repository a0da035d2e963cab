// HeartbeatToRank0: a thread that sends rank 0 an empty message every HEARTBEAT_PERIOD.
#include "MpiHeartbeat.h"

namespace vots::dist {

HeartbeatToRank0::HeartbeatToRank0() : mThread([this] { run(); }) {}

HeartbeatToRank0::~HeartbeatToRank0() {
    {
        std::lock_guard lock(mMutex);
        mStop = true;
    }
    mWake.notify_all();
    mThread.join();
}

void HeartbeatToRank0::run() {
    std::unique_lock lock(mMutex);
    while (!mStop) {
        if (sendDone(mSend)) startSend(mEmpty, 0, ALIVE_TAG, mSend);
        mWake.wait_for(lock, HEARTBEAT_PERIOD, [this] { return mStop; });
    }
}

} // namespace vots::dist
