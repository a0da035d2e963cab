// Splits work among std::threads: a few tasks, one thread each, or [0, n) in one chunk per core.
#pragma once

#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>

namespace vots::render {

/// task(i) for every i in [0, count), each on its own thread (task 0 on the caller's); for a few
/// large, independent pieces of work.
template <class Task> void parallelTasks(std::size_t count, Task&& task) {
    std::vector<std::thread> pool;
    for (std::size_t i = 1; i < count; ++i)
        pool.emplace_back([&task, i] { task(i); });
    if (count > 0) task(std::size_t{0});
    for (auto& t : pool)
        t.join();
}

/// body(first, last) once per chunk; for independent items of even cost (upload preparation).
template <class Body> void parallelChunks(std::size_t n, Body&& body) {
    const std::size_t workers =
        std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, std::max<std::size_t>(n / 1024, 1));
    parallelTasks(workers, [&](std::size_t w) { body(n * w / workers, n * (w + 1) / workers); });
}

} // namespace vots::render
