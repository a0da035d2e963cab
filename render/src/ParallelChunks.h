// Splits [0, n) into one contiguous chunk per core and runs them on std::threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace vots::render {

/// body(first, last) once per chunk; for independent items of even cost (upload preparation).
template <class Body> void parallelChunks(std::size_t n, Body&& body) {
    const std::size_t workers =
        std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, std::max<std::size_t>(n / 1024, 1));
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < workers; ++w)
        pool.emplace_back([&, w] { body(n * w / workers, n * (w + 1) / workers); });
    body(0, n / workers);
    for (auto& t : pool)
        t.join();
}

} // namespace vots::render
