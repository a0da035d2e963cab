// Runs a loop body over [0, n) on a few std::threads with dynamic scheduling; rethrows the first error.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace vots::fit {

inline int resolveThreadCount(int requested) {
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

/// body(index, threadIndex) is called once per index; indices are handed out one at a time.
template <class Body> void parallelFor(std::size_t n, int threads, Body&& body) {
    const int count = std::max(1, std::min<int>(threads, static_cast<int>(std::min<std::size_t>(n, 1024))));
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto worker = [&](int threadIndex) {
        try {
            for (std::size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1))
                body(i, threadIndex);
        } catch (...) {
            std::lock_guard lock(errorMutex);
            if (!error) error = std::current_exception();
            next.store(n); // stop handing out work
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < count; ++t)
        pool.emplace_back(worker, t);
    worker(0);
    for (auto& t : pool)
        t.join();
    if (error) std::rethrow_exception(error);
}

} // namespace vots::fit
