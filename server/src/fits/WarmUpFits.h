// Warm-up fits: while the server is idle, the slider's eps near the last one are fitted ahead, on one thread.
#pragma once

#include "datasets/DatasetRegistry.h"
#include "fits/FitKey.h"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {

class BoxCaches;
class VotSpaceCache;
class ForegroundActivity;

/// Background fits around a finished fit's eps (WarmUpFits::RUNGS), for /api/stats; each eps counts once.
struct WarmUpSummary {
    std::uint64_t started = 0, finished = 0, cancelled = 0, failed = 0;
    bool running = false;
    std::string lastKey; // the latest warm-up's FitKey text
    float lastEps = 0.f;
    double lastSeconds = 0.0;
};

/// A refit at a new eps is bound by the CPU: mostly the first fits of the merge's new unions, which no
/// earlier fit can answer (bench/RESULTS.md, "A slower host"), so a move of the eps slider cannot be
/// made cheap, only made ahead. When a requested fit has finished and nothing waits, one thread at nice
/// 19 fits the dataset at the rung its viewers' drafts are drawn from (draftRung), then at the RUNGS
/// rungs of the slider's ladder (epsLadder) nearest its eps, nearest first, not below FLOOR of its range,
/// and keeps their Vot-Spaces in the fit cache: a move to one of them is a cache hit. Each fit also fills the
/// shared box cache, so the next one and a refit off the ladder cost less. Thread-safe.
class WarmUpFits {
public:
    /// Of the value range: a warm-up below it costs more (time, cache memory) than the rare move it helps.
    static constexpr float FLOOR = 0.01f;
    /// Rungs fitted around a finished fit: five either way, 0.62-1.6x its eps (bench/RESULTS.md, "The
    /// eps slider's ladder").
    static constexpr std::size_t RUNGS = 10;

    WarmUpFits(BoxCaches& boxCaches, VotSpaceCache& spaces, const ForegroundActivity& foreground,
               bool enabled);
    ~WarmUpFits(); // stop(), then joins
    WarmUpFits(const WarmUpFits&) = delete;
    WarmUpFits& operator=(const WarmUpFits&) = delete;

    /// The requested fit `done` has finished, or was found in the cache, and no other fit waits or runs:
    /// its rungs become the warm-ups still to run (replacing those of an earlier fit: the hand is here
    /// now), started at once or after the running one. Not for a focus fit; of the rungs, those run
    /// already or below FLOOR are left out.
    void afterIdleFit(std::shared_ptr<const Dataset> dataset, const FitKey& done);
    /// A requested fit arrived: the running warm-up is cancelled and the rest dropped (they may run again
    /// after the next idle fit).
    void giveWay();
    /// Starts no more and cancels the running one; idempotent.
    void stop();
    WarmUpSummary summary() const;

private:
    enum class End { Finished, Cancelled, Failed };
    /// Runs the pending keys in turn until none is left or they are cancelled; those not finished may run
    /// again later (a cancelled one from where it got to in the box cache), a failed one is not tried
    /// again.
    void run();
    /// Forgets the pending keys, so that a later fit may warm them up again.
    void dropPendingLocked();
    /// Whether the fit cache (memory, then disk) holds the key's Vot-Space.
    bool inFitCache(const FitKey& key);
    /// One warm-up fit, giving way to frames between bricks; its Vot-Space goes to the fit cache.
    End fitOne(const Dataset& dataset, const FitKey& key);

    BoxCaches& mBoxCaches;
    VotSpaceCache& mSpaces;
    const ForegroundActivity& mForeground;
    const bool mEnabled;
    std::atomic<bool> mCancel{false};

    mutable std::mutex mMutex;
    bool mStopping = false;
    // A requested fit came (giveWay): the pending keys are dropped before the next warm-up starts, unless
    // an idle fit's rungs have replaced them since. mCancel, set with it, stops the running warm-up only.
    bool mDropPending = false;
    WarmUpSummary mSummary;
    std::shared_ptr<const Dataset> mDataset; // of the pending keys
    std::vector<FitKey> mPending;            // nearest first
    std::set<std::string> mWarmed;           // keys already run (or running)
    std::thread mThread;
};

} // namespace vots::server
