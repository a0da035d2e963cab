// Counters for /api/stats: recent frame times (last, median) and recent fits; thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace vots::server {

/// One finished fit as /api/stats lists it.
struct FitRecord {
    std::string key;
    std::string dataset;
    float eps = 0.f;
    int degree = 3;
    std::size_t votCount = 0;
    double fitSeconds = 0.0;
    std::string source; // "fit", "disk" or "ranks" (under mpirun)
};

struct FrameSummary {
    std::uint64_t frames = 0; // frames rendered since start
    double lastMs = 0.0;
    double medianMs = 0.0; // over the last WINDOW frames
    std::uint64_t superseded = 0;
};

class ServerStats {
public:
    static constexpr std::size_t WINDOW = 256;

    void addFrame(double ms);
    void addSuperseded();
    void addFit(FitRecord record);
    FrameSummary frames() const;
    std::vector<FitRecord> fits() const; // most recent last, at most WINDOW

private:
    mutable std::mutex mMutex;
    std::deque<double> mFrameMs;
    std::uint64_t mFrames = 0;
    std::uint64_t mSuperseded = 0;
    std::deque<FitRecord> mFits;
};

} // namespace vots::server
