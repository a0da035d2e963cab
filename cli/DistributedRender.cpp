// `vots render` under mpirun: slabs of the grid's z cells per rank, and the composite on rank 0.
#include "DistributedRender.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vots::cli {

ZSlab zSlabOfRank(int cellsZ, int rank, int ranks) {
    const auto at = [&](int r) { return static_cast<int>(static_cast<long long>(cellsZ) * r / ranks); };
    return {at(rank), at(rank + 1)};
}

fit::VotSpace votsOfSlab(fit::VotSpace space, ZSlab slab) {
    std::erase_if(space.vots,
                  [&](const fit::Vot& v) { return v.box.lo[2] < slab.first || v.box.lo[2] >= slab.end; });
    return space;
}

fit::Volume planesOfSlab(const fit::Volume& volume, ZSlab slab) {
    if (volume.isCompact()) throw fit::InputError("planesOfSlab needs float samples");
    fit::Volume part = volume;
    part.values.clear();
    const std::size_t plane =
        static_cast<std::size_t>(volume.dims[0]) * static_cast<std::size_t>(volume.dims[1]);
    part.dims[2] = slab.end - slab.first + 1;
    part.values.assign(volume.values.begin() + static_cast<std::ptrdiff_t>(plane * slab.first),
                       volume.values.begin() + static_cast<std::ptrdiff_t>(plane * (slab.end + 1)));
    for (int w = 0; w < 3; ++w)
        part.origin[w] += volume.patientAxes[2][w] * volume.spacing[2] * slab.first;
    return part;
}

void placeSlabFitInGrid(fit::VotSpace& space, ZSlab slab, const fit::Volume& whole) {
    for (fit::Vot& v : space.vots) {
        v.box.lo[2] += slab.first;
        v.box.hi[2] += slab.first;
        v.p[2] += static_cast<float>(slab.first);
    }
    space.dims = whole.dims;
    space.origin = whole.origin;
    space.spacing = whole.spacing;
    space.patientAxes = whole.patientAxes;
    space.orientationKnown = whole.orientationKnown;
}

void compositeOnRoot(const MpiWorld& world, render::RenderMode mode, render::FloatImage& frame) {
    if (mode == render::RenderMode::Mip) {
        world.reduceMaxToRoot(frame.pixels);
        return;
    }
    if (mode != render::RenderMode::Density)
        throw fit::InputError(std::string(render::renderModeName(mode)) +
                              " is not composited across ranks yet");
    world.reduceMinToRoot(frame.pixels); // the smallest Vot along the ray; no Vot is +inf on every rank
}

} // namespace vots::cli
