// Foreground work (frames, requested fits) that background work (warm-ups, cache files) gives way to.
#pragma once

#include <chrono>
#include <mutex>

namespace vots::server {

enum class Foreground { Frame, Fit };

/// Thread-safe. Counts what is in flight and remembers when each kind last ended.
class ForegroundActivity {
public:
    void begin(Foreground work); // a frame or a requested fit starts (ForegroundMark pairs these)
    void end(Foreground work);   // and ends, done or not
    /// Whether a frame is being drawn or ended less than `quiet` ago (warm-up fits wait).
    bool renderedWithin(std::chrono::milliseconds quiet) const;
    /// Whether a frame or a requested fit is running or ended less than `quiet` ago (cache files wait).
    bool busyWithin(std::chrono::milliseconds quiet) const;

private:
    struct InFlight {
        int count = 0;
        std::chrono::steady_clock::time_point lastEnd{};
        bool within(std::chrono::milliseconds quiet) const {
            return count > 0 || std::chrono::steady_clock::now() - lastEnd < quiet;
        }
    };
    InFlight& inFlight(Foreground work) { return work == Foreground::Frame ? mFrameWork : mFitWork; }

    mutable std::mutex mMutex;
    InFlight mFrameWork, mFitWork;
};

/// begin(work) now, end(work) when the scope ends, also by an exception.
class ForegroundMark {
public:
    ForegroundMark(ForegroundActivity& activity, Foreground work) : mActivity(activity), mWork(work) {
        mActivity.begin(mWork);
    }
    ~ForegroundMark() { mActivity.end(mWork); }
    ForegroundMark(const ForegroundMark&) = delete;
    ForegroundMark& operator=(const ForegroundMark&) = delete;

private:
    ForegroundActivity& mActivity;
    Foreground mWork;
};

} // namespace vots::server
