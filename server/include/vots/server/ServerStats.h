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

class ServerStats;

/// beginFrame() now, endFrame() when the scope ends, also by an exception.
class FrameMark {
public:
    explicit FrameMark(ServerStats& stats);
    ~FrameMark();
    FrameMark(const FrameMark&) = delete;
    FrameMark& operator=(const FrameMark&) = delete;

private:
    ServerStats& mStats;
};

class ServerStats {
public:
    static constexpr std::size_t WINDOW = 256;

    void beginFrame(); // the render thread starts drawing (FrameMark below pairs these)
    void endFrame();   // and stops, drawn or not
    void addFrame(double ms);
    /// Whether a frame is being drawn or ended less than `quiet` ago: background work gives way.
    bool renderedWithin(std::chrono::milliseconds quiet) const;
    void addSuperseded();
    void addFit(FitRecord record);
    FrameSummary frames() const;
    std::vector<FitRecord> fits() const; // most recent last, at most WINDOW

private:
    mutable std::mutex mMutex;
    std::deque<double> mFrameMs;
    std::uint64_t mFrames = 0;
    std::uint64_t mSuperseded = 0;
    int mFramesInFlight = 0;
    std::chrono::steady_clock::time_point mLastFrameEnd{};
    std::deque<FitRecord> mFits;
};

} // namespace vots::server
