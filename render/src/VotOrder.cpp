// Record orders for the two MIP strategies.
#include "VotOrder.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace vots::render {

namespace {

// Spreads the low 21 bits of v to every third bit.
std::uint64_t spreadBits(std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

// Sorts indices by key on contiguous (key, index) pairs: sorting indices through a key lookup missed
// the cache on every comparison.
template <typename Key> std::vector<std::size_t> orderByKey(std::vector<std::pair<Key, std::size_t>> keys) {
    std::sort(keys.begin(), keys.end());
    std::vector<std::size_t> order(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i)
        order[i] = keys[i].second;
    return order;
}

} // namespace

std::vector<std::size_t> spatialOrder(const std::vector<fit::Vot>& vots) {
    std::vector<std::uint64_t> keys(vots.size());
    std::uint64_t all = 0;
    for (std::size_t i = 0; i < vots.size(); ++i) {
        const auto& lo = vots[i].box.lo;
        const auto bits = [](int v) { return spreadBits(static_cast<std::uint64_t>(std::max(v, 0))); };
        keys[i] = bits(lo[0]) | bits(lo[1]) << 1 | bits(lo[2]) << 2;
        all |= keys[i];
    }
    // Least significant digit first, 11 bits at a time, stable: equal keys keep file order, as a
    // comparison sort on (key, index) would give, in a few linear passes instead of log2(n) comparisons
    // per Vot (a refit waits for the upload this is part of).
    constexpr int DIGIT_BITS = 11;
    constexpr std::size_t BUCKETS = std::size_t{1} << DIGIT_BITS;
    std::vector<std::size_t> order(vots.size()), next(vots.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = i;
    for (int shift = 0; shift < 64 && (all >> shift) != 0; shift += DIGIT_BITS) {
        std::vector<std::size_t> start(BUCKETS + 1, 0);
        for (const std::uint64_t key : keys)
            ++start[((key >> shift) & (BUCKETS - 1)) + 1];
        for (std::size_t b = 0; b < BUCKETS; ++b)
            start[b + 1] += start[b];
        for (const std::size_t i : order)
            next[start[(keys[i] >> shift) & (BUCKETS - 1)]++] = i;
        order.swap(next);
    }
    return order;
}

std::vector<std::size_t> boundOrder(const std::vector<GpuVot>& vots) {
    std::vector<std::pair<float, std::size_t>> keys(vots.size());
    for (std::size_t i = 0; i < vots.size(); ++i)
        keys[i] = {-vots[i].upperBound, i};
    return orderByKey(std::move(keys));
}

} // namespace vots::render
