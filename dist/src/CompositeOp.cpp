// The composite table and the per-pixel arithmetic every composite of the ranks' frames uses.
#include "vots/dist/CompositeOp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace vots::dist {

CompositeOp compositeOpFor(render::RenderMode mode, RankSource source) {
    const bool grid = source == RankSource::Grid;
    switch (mode) {
    case render::RenderMode::Mip:
        return CompositeOp::Max;
    case render::RenderMode::MinIp:
        // The grid draws each rank's cells with the whole ray (GridRenderer::uploadPlanes): +inf where its
        // ray takes nothing, as where one process's misses.
        return grid ? CompositeOp::Min : CompositeOp::MinOfCutRays;
    case render::RenderMode::Aip:
        return grid ? CompositeOp::Sum : CompositeOp::WeightedMean;
    case render::RenderMode::Density:
        if (grid) break;
        return CompositeOp::Min;
    }
    throw std::logic_error("compositeOpFor: the grid draws no density");
}

bool compositesCutRays(render::RenderMode mode) {
    const CompositeOp op = compositeOpFor(mode, RankSource::Vots);
    return op == CompositeOp::MinOfCutRays || op == CompositeOp::WeightedMean;
}

render::CellDomain cutRayDomainOf(RankCells cells, const std::array<int, 3>& dims) {
    return {{0, 0, cells.first}, {dims[0] - 1, dims[1] - 1, cells.end}};
}

void minOfCutRaysForCombining(std::vector<float>& pixels) {
    for (float& v : pixels)
        if (v == -INFINITY) v = INFINITY;
}

void minOfCutRaysFromCombined(std::vector<float>& pixels) {
    for (float& v : pixels)
        if (v == INFINITY) v = -INFINITY;
}

void combineExtremes(CompositeOp op, std::vector<float>& into, const std::vector<float>& other) {
    if (other.size() != into.size()) throw std::runtime_error("a rank's frame has another size");
    switch (op) {
    case CompositeOp::Max:
        for (std::size_t i = 0; i < into.size(); ++i)
            into[i] = std::max(into[i], other[i]);
        return;
    case CompositeOp::Min:
    case CompositeOp::MinOfCutRays:
        for (std::size_t i = 0; i < into.size(); ++i)
            into[i] = std::min(into[i], other[i]);
        return;
    case CompositeOp::WeightedMean:
    case CompositeOp::Sum:
        break;
    }
    throw std::logic_error("combineExtremes: the sums add their parts");
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

void addSumPart(std::vector<double>& sums, const std::vector<float>& part) {
    if (part.size() != sums.size()) throw std::runtime_error("a rank's frame has another size");
    for (std::size_t i = 0; i < sums.size(); ++i)
        sums[i] += part[i];
}

void sumsToFrame(const std::vector<double>& sums, render::FloatImage& frame) {
    if (sums.size() != frame.pixels.size()) throw std::logic_error("sumsToFrame: sizes differ");
    for (std::size_t i = 0; i < sums.size(); ++i)
        frame.pixels[i] = static_cast<float>(sums[i]);
}

} // namespace vots::dist
