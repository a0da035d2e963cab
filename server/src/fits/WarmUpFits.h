// Warm-up fits: while the server is idle, half the last eps is fitted into the box cache, on one thread.
#pragma once

#include "datasets/DatasetRegistry.h"
#include "fits/FitKey.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace vots::server {

class BoxCaches;
class ForegroundActivity;

/// Background fits at half a finished fit's eps, for /api/stats.
struct WarmUpSummary {
    std::uint64_t started = 0, finished = 0, cancelled = 0, failed = 0;
    bool running = false;
    std::string lastKey; // the latest warm-up's FitKey text
    float lastEps = 0.f;
    double lastSeconds = 0.0;
};

/// A move of the eps slider to a smaller eps must fit boxes no earlier fit tried, which makes it the
/// slowest move. So when a requested fit has finished and nothing waits, one thread at nice 19 fits
/// the dataset at half that eps (not below FLOOR of its range) into the shared box cache; a later
/// refit anywhere between the two answers most boxes from the cache. Its Vot-Space is dropped: only
/// the cache is wanted. Thread-safe.
class WarmUpFits {
public:
    /// Of the value range: a warm-up below it costs more (time, cache memory) than the rare move it helps.
    static constexpr float FLOOR = 0.01f;

    WarmUpFits(BoxCaches& boxCaches, const ForegroundActivity& foreground, bool enabled);
    ~WarmUpFits(); // stop(), then joins
    WarmUpFits(const WarmUpFits&) = delete;
    WarmUpFits& operator=(const WarmUpFits&) = delete;

    /// The requested fit `done` has finished and no other fit waits or runs: starts its warm-up unless
    /// one runs, it was run already, it is a focus fit, or it would fall below FLOOR.
    void afterIdleFit(std::shared_ptr<const Dataset> dataset, const FitKey& done);
    /// A requested fit arrived: the running warm-up is cancelled (it may run again later).
    void giveWay();
    /// Starts no more and cancels the running one; idempotent.
    void stop();
    WarmUpSummary summary() const;

private:
    void run(std::shared_ptr<const Dataset> dataset, const FitKey& key);

    BoxCaches& mBoxCaches;
    const ForegroundActivity& mForeground;
    const bool mEnabled;
    std::atomic<bool> mCancel{false};

    mutable std::mutex mMutex;
    bool mStopping = false;
    WarmUpSummary mSummary;
    std::set<std::string> mWarmed; // keys already run (or running)
    std::thread mThread;
};

} // namespace vots::server
