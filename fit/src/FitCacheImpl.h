// FitCache internals: box -> certified error and coefficients, sharded by hash for two or more threads.
#pragma once

#include "BoxFit.h"
#include "CellMask.h"
#include "vots/fit/Fitter.h"

#include <absl/container/flat_hash_map.h>
#include <absl/hash/hash.h>

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>

namespace vots::fit {

struct BoxHash {
    std::size_t operator()(const Box& b) const noexcept { return absl::HashOf(b.lo, b.hi); }
};
// Six int compares, inlined: Box's defaulted == compiles to a memcmp call, on the hottest path of a refit.
struct BoxEqual {
    bool operator()(const Box& a, const Box& b) const noexcept {
        return a.lo[0] == b.lo[0] && a.lo[1] == b.lo[1] && a.lo[2] == b.lo[2] && a.hi[0] == b.hi[0] &&
               a.hi[1] == b.hi[1] && a.hi[2] == b.hi[2];
    }
};

/// A fitted box as remembered across fits. The least-squares solution does not depend on eps, so an
/// exact error decides acceptance at any uniform eps without touching the samples again.
struct CachedBox {
    BoxOutcome outcome; // coefficients valid only when fitted (not for an RSS early reject)
    bool hasCoefficients = false;
    // Minimax acceptance only (BoxRecord): the lower bound, the state (NotRun or Centred), and where the
    // shard keeps the centred polynomial (few boxes have one, so it is not inline).
    float lowerBound = 0.f;
    BoxRecord::Minimax minimaxState = BoxRecord::Minimax::NotRun;
    std::uint32_t minimaxEntry = NO_ENTRY;
    static constexpr std::uint32_t NO_ENTRY = 0xffffffffu;
};

/// A box's centred least-squares polynomial (BoxRecord's) and, when it was accepted, its certification.
struct CachedMinimax {
    BoxOutcome outcome;
    float centredHalfRange = NAN;
    float centredConstant = 0.f;
};

struct FitCache::Impl {
    // Shards by position: the boxes of one zone (32^3 cells, SplitMerge.h) share a shard, so a zone's split
    // (hundreds of lookups in a row) works in one small table that stays in cache, instead of missing into a
    // table of millions of entries at every lookup.
    static constexpr std::size_t SHARDS = 1024;
    static constexpr int SHARD_CELLS_LOG2 = 5;
    struct Shard {
        std::mutex mutex;
        // Open addressing over small slots (box -> entry number): a lookup costs about one cache miss,
        // and misses never touch the large entries (a node map, or a flat map with the entries inline,
        // would touch them).
        absl::flat_hash_map<Box, std::uint32_t, BoxHash, BoxEqual> index;
        std::deque<CachedBox> entries;       // never moves an entry
        std::deque<CachedMinimax> minimaxes; // CachedBox::minimaxEntry
    };
    std::array<Shard, SHARDS> shards;
    // Identity of what the cached errors belong to; a mismatch clears the cache.
    const void* volumeData = nullptr; // the bound volume's samples (float or compact)
    std::array<int, 3> dims{0, 0, 0};
    int degree = -1;
    Certify certify = Certify::Samples;
    FitNorm norm = FitNorm::Lsq;

    // The background mask of the bound volume: the same for every refit at the same background, and
    // built on the fit's serial path.
    std::mutex maskMutex;
    std::shared_ptr<const CellMask> mask;
    std::optional<float> maskBackground;
    std::optional<float> maskNoData;

    static std::size_t shardOf(const Box& box) {
        const auto zone = [&](int a) { return static_cast<std::size_t>(box.lo[a] >> SHARD_CELLS_LOG2); };
        return (zone(0) * 73856093u ^ zone(1) * 19349663u ^ zone(2) * 83492791u) % SHARDS;
    }
    void bind(const Volume& volume, int degreeIn, Certify certifyIn, FitNorm normIn);
    std::shared_ptr<const CellMask> maskFor(const Volume& volume, std::optional<float> background,
                                            std::optional<float> noDataValue);
    std::optional<CachedBox> find(const Box& box);
    /// Starts loading where find(box) will look, so that lookups coming soon overlap their cache misses.
    void prefetch(const Box& box);
    void store(const Box& box, const CachedBox& entry);
    /// Minimax acceptance: what is known of the box, into `record` (left empty when nothing is).
    void find(const Box& box, BoxRecord& record);
    void store(const Box& box, const BoxRecord& record);
    std::size_t size();
    std::size_t memoryBytes();
};

} // namespace vots::fit
