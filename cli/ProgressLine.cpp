// Fit progress on stderr; throttled so fitting threads never wait long on the terminal.
#include "ProgressLine.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vots::cli {

ProgressLine::ProgressLine(bool enabled)
    : mEnabled(enabled), mIsTerminal(::isatty(STDERR_FILENO) == 1), mStart(std::chrono::steady_clock::now()) {
}

ProgressLine::~ProgressLine() {
    finish();
}

void ProgressLine::update(double fraction, const char* stage) {
    if (!mEnabled) return;
    const int percent = static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0));
    const std::string name = stage ? stage : "";
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mMutex);
    const bool newStage = name != mStage;
    if (newStage) {
        mStage = name;
        mLastDecile = -1;
    }
    if (mIsTerminal) {
        // Redraw on a new stage or percent, at most ten times a second.
        if (!newStage && (percent == mLastPercent || now - mLastDraw < std::chrono::milliseconds(100)))
            return;
    } else {
        // A log file gets a line per stage and per 10 %.
        if (percent / 10 == mLastDecile) return;
        mLastDecile = percent / 10;
    }
    mLastPercent = percent;
    mLastDraw = now;
    print(percent, name);
}

void ProgressLine::print(int percent, const std::string& stage) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
    if (mIsTerminal) {
        // \033[K clears what a longer previous line left behind.
        std::fprintf(stderr, "\rfit: %-10s %3d %%  %6.1f s\033[K", stage.c_str(), percent, seconds);
        mLineOpen = true;
    } else {
        std::fprintf(stderr, "fit: %s %d %% (%.1f s)\n", stage.c_str(), percent, seconds);
    }
    std::fflush(stderr);
}

void ProgressLine::finish() {
    std::lock_guard lock(mMutex);
    if (mLineOpen) std::fputc('\n', stderr);
    mLineOpen = false;
}

} // namespace vots::cli
