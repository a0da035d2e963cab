// `vots render` under mpirun: which Vots and cells each rank draws, and the composite on rank 0.
#include "DistributedRender.h"

#include <algorithm>
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

void minIpForCombining(std::vector<float>& pixels) {
    for (float& v : pixels)
        if (v == -INFINITY) v = INFINITY;
}

void minIpFromCombined(std::vector<float>& pixels) {
    for (float& v : pixels)
        if (v == INFINITY) v = -INFINITY;
}

void combineExtremes(render::RenderMode mode, std::vector<float>& into, const std::vector<float>& other) {
    if (other.size() != into.size()) throw std::runtime_error("a rank's frame has another size");
    if (mode == render::RenderMode::Mip) {
        for (std::size_t i = 0; i < into.size(); ++i)
            into[i] = std::max(into[i], other[i]);
        return;
    }
    if (mode == render::RenderMode::Aip) throw std::logic_error("combineExtremes: the aip adds its parts");
    for (std::size_t i = 0; i < into.size(); ++i)
        into[i] = std::min(into[i], other[i]);
}

void addMeanParts(std::vector<double>& sums, const render::FloatImage& means,
                  const render::FloatImage& lengths) {
    const std::size_t count = means.pixels.size();
    if (lengths.pixels.size() != count || sums.size() != 2 * count)
        throw std::runtime_error("a rank's aip frame has another size");
    // A float's product with a float is exact in double, so the sum over the ranks rounds only where it adds.
    for (std::size_t i = 0; i < count; ++i) {
        const float mean = means.pixels[i], length = lengths.pixels[i];
        if (!std::isfinite(mean) || !(length > 0.f)) continue; // this rank's ray misses its cells
        sums[i] += double(mean) * double(length);
        sums[count + i] += double(length);
    }
}

void meansFromParts(const std::vector<double>& sums, render::FloatImage& means) {
    const std::size_t count = means.pixels.size();
    if (sums.size() != 2 * count) throw std::logic_error("meansFromParts: sizes differ");
    for (std::size_t i = 0; i < count; ++i)
        means.pixels[i] = sums[count + i] > 0.0 ? static_cast<float>(sums[i] / sums[count + i]) : -INFINITY;
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
        minIpForCombining(frame.pixels);
        world.reduceMinToRoot(frame.pixels);
        minIpFromCombined(frame.pixels);
        return;
    case render::RenderMode::Aip:
        break;
    }
    throw std::logic_error("compositeOnRoot: the aip composites with its lengths (compositeMeansOnRoot)");
}

void compositeMeansOnRoot(const MpiWorld& world, render::FloatImage& means,
                          const render::FloatImage& lengths) {
    if (lengths.pixels.size() != means.pixels.size())
        throw std::logic_error("compositeMeansOnRoot: sizes differ");
    std::vector<double> sums(2 * means.pixels.size(), 0.0); // the integrals, then the lengths
    addMeanParts(sums, means, lengths);
    world.reduceSumToRoot(sums);
    if (world.rank() == 0) meansFromParts(sums, means);
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
