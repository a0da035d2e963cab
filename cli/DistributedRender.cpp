// `vots render` under mpirun: which Vots and cells each rank draws, and the composite on rank 0.
#include "DistributedRender.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace vots::cli {

bool compositesCutRays(render::RenderMode mode) {
    return mode == render::RenderMode::MinIp || mode == render::RenderMode::Aip;
}

fit::VotSpace votsOfSlab(fit::VotSpace space, ZSlab slab, bool cutRays) {
    std::erase_if(space.vots, [&](const fit::Vot& v) {
        if (cutRays) return v.box.lo[2] >= slab.end || v.box.hi[2] <= slab.first;
        return v.box.lo[2] < slab.first || v.box.lo[2] >= slab.end;
    });
    return space;
}

render::CellDomain cellDomainOfSlab(ZSlab slab, const std::array<int, 3>& dims) {
    return {{0, 0, slab.first}, {dims[0] - 1, dims[1] - 1, slab.end}};
}

void compositeOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame) {
    switch (mode) {
    case render::RenderMode::Mip:
        world.reduceMaxToRoot(frame.pixels);
        return;
    case render::RenderMode::Density:
        world.reduceMinToRoot(frame.pixels); // the smallest Vot along the ray; no Vot is +inf on every rank
        return;
    case render::RenderMode::MinIp:
        // A rank whose cut ray takes nothing has -inf, which must not win the min: +inf while reducing.
        for (float& v : frame.pixels)
            if (v == -INFINITY) v = INFINITY;
        world.reduceMinToRoot(frame.pixels);
        for (float& v : frame.pixels)
            if (v == INFINITY) v = -INFINITY;
        return;
    case render::RenderMode::Aip:
        break;
    }
    throw std::logic_error("compositeOnRoot: the aip composites with its lengths (compositeMeansOnRoot)");
}

void compositeMeansOnRoot(const MpiWorld& world, render::FloatImage& means,
                          const render::FloatImage& lengths) {
    const std::size_t count = means.pixels.size();
    if (lengths.pixels.size() != count) throw std::logic_error("compositeMeansOnRoot: sizes differ");
    // Integrals, then lengths, in double: a float's product with a float is exact in it, so the sum over
    // the ranks rounds only where it adds.
    std::vector<double> sums(2 * count, 0.0);
    for (std::size_t i = 0; i < count; ++i) {
        const float mean = means.pixels[i], length = lengths.pixels[i];
        if (!std::isfinite(mean) || !(length > 0.f)) continue; // this rank's ray misses its cells
        sums[i] = double(mean) * double(length);
        sums[count + i] = double(length);
    }
    world.reduceSumToRoot(sums);
    if (world.rank() != 0) return;
    for (std::size_t i = 0; i < count; ++i)
        means.pixels[i] = sums[count + i] > 0.0 ? static_cast<float>(sums[i] / sums[count + i]) : -INFINITY;
}

void compositeGridOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame) {
    switch (mode) {
    case render::RenderMode::Mip:
        world.reduceMaxToRoot(frame.pixels);
        return;
    case render::RenderMode::MinIp:
        world.reduceMinToRoot(frame.pixels);
        return;
    case render::RenderMode::Aip: {
        // Summed in double: two ranks' parts round once, as the chunks of one process add in float.
        std::vector<double> sums(frame.pixels.begin(), frame.pixels.end());
        world.reduceSumToRoot(sums);
        if (world.rank() == 0)
            for (std::size_t i = 0; i < sums.size(); ++i)
                frame.pixels[i] = static_cast<float>(sums[i]);
        return;
    }
    case render::RenderMode::Density:
        break;
    }
    throw std::logic_error("compositeGridOnRoot: the grid draws no density");
}

double slowestRankMillisSince(const MpiWorld& world, std::chrono::steady_clock::time_point start) {
    const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
    return world.maxOverRanks(took.count());
}

void reportFrameTimes(const MpiWorld& world, double renderMs, double compositeMs) {
    if (world.rank() != 0) return;
    std::cerr << "vots render: " << world.size() << (world.size() == 1 ? " rank" : " ranks") << ", render "
              << std::fixed << std::setprecision(1) << renderMs << " ms, composite " << compositeMs
              << " ms\n";
}

} // namespace vots::cli
