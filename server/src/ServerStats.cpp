// ServerStats: bounded windows of frame times and fit records behind one mutex.
#include "ServerStats.h"

#include <algorithm>

namespace vots::server {

void ServerStats::addFrame(double ms) {
    std::lock_guard lock(mMutex);
    ++mFrames;
    mFrameMs.push_back(ms);
    if (mFrameMs.size() > WINDOW) mFrameMs.pop_front();
}

void ServerStats::addSuperseded() {
    std::lock_guard lock(mMutex);
    ++mSuperseded;
}

void ServerStats::addFit(FitRecord record) {
    std::lock_guard lock(mMutex);
    mFits.push_back(std::move(record));
    if (mFits.size() > WINDOW) mFits.pop_front();
}

FrameSummary ServerStats::frames() const {
    std::lock_guard lock(mMutex);
    FrameSummary summary;
    summary.frames = mFrames;
    summary.superseded = mSuperseded;
    if (mFrameMs.empty()) return summary;
    summary.lastMs = mFrameMs.back();
    std::vector<double> sorted(mFrameMs.begin(), mFrameMs.end());
    const auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), mid, sorted.end());
    summary.medianMs = *mid;
    return summary;
}

std::vector<FitRecord> ServerStats::fits() const {
    std::lock_guard lock(mMutex);
    return {mFits.begin(), mFits.end()};
}

} // namespace vots::server
