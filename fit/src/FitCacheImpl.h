// FitCache internals: box -> certified error and coefficients, sharded by hash for two or more threads.
#pragma once

#include "BoxFit.h"
#include "vots/fit/Fitter.h"

#include <array>
#include <mutex>
#include <optional>
#include <unordered_map>

namespace vots::fit {

struct BoxHash {
    std::size_t operator()(const Box& b) const noexcept {
        std::size_t h = 1469598103934665603ull;
        for (int a = 0; a < 3; ++a) {
            h = (h ^ static_cast<std::size_t>(b.lo[a])) * 1099511628211ull;
            h = (h ^ static_cast<std::size_t>(b.hi[a])) * 1099511628211ull;
        }
        return h ^ (h >> 29);
    }
};

/// A fitted box as remembered across fits. The least-squares solution does not depend on eps, so an
/// exact error decides acceptance at any uniform eps without touching the samples again.
struct CachedBox {
    BoxOutcome outcome; // coefficients valid only when fitted (not for an RSS early reject)
    bool hasCoefficients = false;
};

struct FitCache::Impl {
    static constexpr std::size_t SHARDS = 64;
    struct Shard {
        std::mutex mutex;
        std::unordered_map<Box, CachedBox, BoxHash> boxes;
    };
    std::array<Shard, SHARDS> shards;
    // Identity of what the cached errors belong to; a mismatch clears the cache.
    const float* volumeData = nullptr;
    std::array<int, 3> dims{0, 0, 0};
    int degree = -1;
    Certify certify = Certify::Samples;

    void bind(const Volume& volume, int degreeIn, Certify certifyIn);
    std::optional<CachedBox> find(const Box& box);
    void store(const Box& box, const CachedBox& entry);
    std::size_t size();
};

} // namespace vots::fit
