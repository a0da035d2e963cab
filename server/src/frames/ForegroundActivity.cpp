// ForegroundActivity: in-flight counts and last end times of frames and requested fits, behind one mutex.
#include "frames/ForegroundActivity.h"

#include <algorithm>

namespace vots::server {

void ForegroundActivity::begin(Foreground work) {
    std::lock_guard lock(mMutex);
    ++inFlight(work).count;
}

void ForegroundActivity::end(Foreground work) {
    std::lock_guard lock(mMutex);
    InFlight& w = inFlight(work);
    w.count = std::max(0, w.count - 1);
    w.lastEnd = std::chrono::steady_clock::now();
}

bool ForegroundActivity::renderedWithin(std::chrono::milliseconds quiet) const {
    std::lock_guard lock(mMutex);
    return mFrameWork.within(quiet);
}

bool ForegroundActivity::busyWithin(std::chrono::milliseconds quiet) const {
    std::lock_guard lock(mMutex);
    return mFrameWork.within(quiet) || mFitWork.within(quiet);
}

} // namespace vots::server
