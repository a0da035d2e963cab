// Fit progress on stderr: one updating line on a terminal, a line every ~10 % otherwise; thread-safe.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace vots::cli {

class ProgressLine {
public:
    /// Writes nothing when disabled; detects a terminal on stderr itself.
    explicit ProgressLine(bool enabled);
    ~ProgressLine();
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    /// Called from fitting threads; fraction in [0, 1].
    void update(double fraction, const char* stage);
    /// Ends the updating line (terminal) so later output starts on a fresh line.
    void finish();

private:
    void print(int percent, const std::string& stage);

    bool mEnabled;
    bool mIsTerminal;
    std::mutex mMutex;
    std::string mStage;
    int mLastPercent = -1;
    int mLastDecile = -1;
    bool mLineOpen = false;
    std::chrono::steady_clock::time_point mStart;
    std::chrono::steady_clock::time_point mLastDraw;
};

} // namespace vots::cli
