// The frames of 4D datasets held beside their frame 0: in the order of use, within a bound of bytes.
#pragma once

#include <cstdint>
#include <functional>
#include <list>
#include <string>
#include <vector>

namespace vots::server {

/// What GET /api/stats reports of the held frames.
struct HeldFramesSummary {
    std::uint64_t bytes = 0;         // their samples, as estimated from the header
    std::uint64_t boundBytes = 0;    // what they are held within
    std::vector<std::string> frames; // "<dataset>/<frame>", least recently used first
};

/// Not thread-safe: DatasetRegistry calls it under its mutex.
class HeldFrames {
public:
    explicit HeldFrames(std::uint64_t boundBytes) : mBound(boundBytes) {}

    /// Frame `frame` of `dataset`, used now: the most recently used.
    void touch(const std::string& dataset, int frame);
    /// Drops the least recently used, calling `drop(dataset, frame)` for each, until `bytes` more stay within
    /// the bound and `admits()` (the memory budget) says yes, or none is left.
    void makeRoom(std::uint64_t bytes, const std::function<bool()>& admits,
                  const std::function<void(const std::string&, int)>& drop);
    /// A frame just loaded, the most recently used.
    void add(const std::string& dataset, int frame, std::uint64_t bytes);
    /// Forgets every frame of `dataset` (its files changed).
    void forget(const std::string& dataset);
    HeldFramesSummary summary() const;

private:
    struct Held {
        std::string dataset;
        int frame = 0;
        std::uint64_t bytes = 0;
    };
    const std::uint64_t mBound;
    std::list<Held> mUse; // least recently used first
    std::uint64_t mBytes = 0;
};

} // namespace vots::server
