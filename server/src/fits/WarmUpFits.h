// Warm-up fits: while the server is idle, eps near the last one are fitted into the box cache, on one thread.
#pragma once

#include "datasets/DatasetRegistry.h"
#include "fits/FitKey.h"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {

class BoxCaches;
class ForegroundActivity;

/// Background fits around a finished fit's eps (WarmUpFits::FACTORS), for /api/stats; each eps counts once.
struct WarmUpSummary {
    std::uint64_t started = 0, finished = 0, cancelled = 0, failed = 0;
    bool running = false;
    std::string lastKey; // the latest warm-up's FitKey text
    float lastEps = 0.f;
    double lastSeconds = 0.0;
};

/// A move of the eps slider spends most of its refit fitting boxes no earlier fit tried: deeper boxes
/// going down, the unions its merges meet going up. So when a requested fit has finished and nothing
/// waits, one thread at nice 19 fits the dataset at the eps of FACTORS in turn (not below FLOOR of its
/// range) into the shared box cache; a later refit near them answers most boxes from the cache. Their
/// Vot-Spaces are dropped: only the cache is wanted. Thread-safe.
class WarmUpFits {
public:
    /// Of the value range: a warm-up below it costs more (time, cache memory) than the rare move it helps.
    static constexpr float FLOOR = 0.01f;
    /// The warm-ups' eps as multiples of the finished fit's, in the order they run: a step down (the
    /// costliest kind of move), a step up, then a far move down (bench/RESULTS.md, "Warm-ups around the
    /// slider's eps").
    static constexpr std::array<float, 3> FACTORS{0.8f, 1.25f, 0.5f};

    WarmUpFits(BoxCaches& boxCaches, const ForegroundActivity& foreground, bool enabled);
    ~WarmUpFits(); // stop(), then joins
    WarmUpFits(const WarmUpFits&) = delete;
    WarmUpFits& operator=(const WarmUpFits&) = delete;

    /// The requested fit `done` has finished and no other fit waits or runs: starts its warm-ups unless
    /// one runs or it is a focus fit; of FACTORS, those run already or below FLOOR are left out.
    void afterIdleFit(std::shared_ptr<const Dataset> dataset, const FitKey& done);
    /// A requested fit arrived: the running warm-up is cancelled (it may run again later).
    void giveWay();
    /// Starts no more and cancels the running one; idempotent.
    void stop();
    WarmUpSummary summary() const;

private:
    enum class End { Finished, Cancelled, Failed };
    /// Runs the keys in turn until one does not finish; those not finished may run again later (a
    /// cancelled one from where it got to in the box cache), a failed one is not tried again.
    void run(std::shared_ptr<const Dataset> dataset, const std::vector<FitKey>& keys);
    /// One warm-up fit, giving way to frames between bricks.
    End fitOne(const Dataset& dataset, const FitKey& key);

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
