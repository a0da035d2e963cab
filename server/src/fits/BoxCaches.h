// The fitter's box caches, one per (dataset, frame, degree), shared by fits and warm-ups, within a budget.
#pragma once

#include "vots/fit/Fitter.h"

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>

namespace vots::server {

struct BoxCacheStats {
    std::size_t caches = 0;  // kept now
    std::uint64_t bytes = 0; // what they hold (fit::FitCache::memoryBytes), as of the last fit's start
    std::uint64_t budgetBytes = 0;
    std::size_t dropped = 0; // caches let go over the budget (or beyond MAX_KEPT) so far
};

/// Thread-safe. A cache grows with every fit at a new eps (each new union of boxes it tries is
/// remembered), so without a bound a server whose eps slider is used for long would fill its memory
/// budget with them, and then refuse every load and fit (507). Before each fit, beyond the budget the
/// least recently used other caches are let go, and then, if it alone is over it, the asked-for cache
/// itself: that fit starts a new one (a fit still running keeps the old one alive until it ends).
class BoxCaches {
public:
    /// Beyond this many, the least recently used is dropped whatever the bytes.
    static constexpr std::size_t MAX_KEPT = 4;

    explicit BoxCaches(std::uint64_t budgetBytes) : mBudget(budgetBytes) {}

    /// The cache for fits of this dataset's frame (of a 4D one; else 0) at this degree, made on first use.
    std::shared_ptr<fit::FitCache> forFits(const std::string& dataset, int frame, int degree);
    BoxCacheStats stats() const;

private:
    struct Kept {
        std::string name; // "dataset/frame/degree"
        std::shared_ptr<fit::FitCache> cache;
        std::uint64_t bytes = 0; // its memoryBytes() at the last fit's start
    };
    const std::uint64_t mBudget;
    mutable std::mutex mMutex;
    std::list<Kept> mKept; // most recently used first
    std::uint64_t mBytes = 0;
    std::size_t mDropped = 0;
};

} // namespace vots::server
