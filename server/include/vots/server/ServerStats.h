// Counters for /api/stats: recent frame times (last, median) and recent fits; thread-safe.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace vots::server {

struct FitRecord {
    std::string key;
    std::string dataset;
    float eps = 0.f;
    int degree = 3;
    std::size_t votCount = 0;
    double fitSeconds = 0.0;
    std::string source; // "fit" or "disk"
};

struct FrameSummary {
    std::uint64_t frames = 0; // frames rendered since start
    double lastMs = 0.0;
    double medianMs = 0.0; // over the last WINDOW frames
    std::uint64_t superseded = 0;
};

/// Foreground work that background work (warm-up fits, cache files) gives way to.
enum class Foreground { Frame, Fit };

class ServerStats {
public:
    static constexpr std::size_t WINDOW = 256;

    void begin(Foreground work); // a frame or a requested fit starts (ForegroundMark pairs these)
    void end(Foreground work);   // and ends, done or not
    void addFrame(double ms);
    /// Whether a frame is being drawn or ended less than `quiet` ago (warm-up fits wait).
    bool renderedWithin(std::chrono::milliseconds quiet) const;
    /// Whether a frame or a requested fit is running or ended less than `quiet` ago (cache files wait).
    bool busyWithin(std::chrono::milliseconds quiet) const;
    void addSuperseded();
    void addFit(FitRecord record);
    FrameSummary frames() const;
    std::vector<FitRecord> fits() const; // most recent last, at most WINDOW

private:
    mutable std::mutex mMutex;
    std::deque<double> mFrameMs;
    std::uint64_t mFrames = 0;
    std::uint64_t mSuperseded = 0;
    struct InFlight {
        int count = 0;
        std::chrono::steady_clock::time_point lastEnd{};
        bool within(std::chrono::milliseconds quiet) const {
            return count > 0 || std::chrono::steady_clock::now() - lastEnd < quiet;
        }
    };
    InFlight mFrameWork, mFitWork;
    std::deque<FitRecord> mFits;
    InFlight& inFlight(Foreground work) { return work == Foreground::Frame ? mFrameWork : mFitWork; }
};

/// begin(work) now, end(work) when the scope ends, also by an exception.
class ForegroundMark {
public:
    ForegroundMark(ServerStats& stats, Foreground work) : mStats(stats), mWork(work) { mStats.begin(mWork); }
    ~ForegroundMark() { mStats.end(mWork); }
    ForegroundMark(const ForegroundMark&) = delete;
    ForegroundMark& operator=(const ForegroundMark&) = delete;

private:
    ServerStats& mStats;
    Foreground mWork;
};

} // namespace vots::server
