// Timing helpers shared by the benchmarks: wall time of a call, medians of interleaved rounds.
#pragma once

#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace vots::bench {

using Clock = std::chrono::steady_clock;

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

inline double msOf(const std::function<void()>& fn) {
    const auto t0 = Clock::now();
    fn();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Runs the functions round-robin (warm-up rounds first) and returns each one's median wall time, ms:
/// load from other processes hits all of them alike.
inline std::vector<double> interleavedMedians(int warmup, int frames,
                                              const std::vector<std::function<void()>>& fns) {
    std::vector<std::vector<double>> ms(fns.size());
    for (int round = 0; round < warmup + frames; ++round)
        for (std::size_t i = 0; i < fns.size(); ++i) {
            const double t = msOf(fns[i]);
            if (round >= warmup) ms[i].push_back(t);
        }
    std::vector<double> out;
    for (const auto& m : ms)
        out.push_back(median(m));
    return out;
}

} // namespace vots::bench
