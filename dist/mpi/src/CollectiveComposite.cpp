// `vots render` under mpirun: the composite on rank 0 by MPI reductions, and the frame's times.
#include "vots/dist/mpi/CollectiveComposite.h"

#include <iomanip>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace vots::dist {

void compositeOnRoot(const MpiWorld& world, CompositeOp op, render::FloatImage& frame,
                     const std::optional<render::FloatImage>& lengths) {
    switch (op) {
    case CompositeOp::Max:
        world.reduceMaxToRoot(frame.pixels);
        return;
    case CompositeOp::Min:
        world.reduceMinToRoot(frame.pixels);
        return;
    case CompositeOp::MinOfCutRays:
        minOfCutRaysForCombining(frame.pixels);
        world.reduceMinToRoot(frame.pixels);
        minOfCutRaysFromCombined(frame.pixels);
        return;
    case CompositeOp::WeightedMean: {
        if (!lengths) throw std::logic_error("compositeOnRoot: the weighted mean needs the ray lengths");
        std::vector<double> sums(2 * frame.pixels.size(), 0.0); // the integrals, then the lengths
        addMeanParts(sums, frame, *lengths);
        world.reduceSumToRoot(sums);
        if (world.rank() == 0) meansFromParts(sums, frame);
        return;
    }
    case CompositeOp::Sum: {
        std::vector<double> sums(frame.pixels.size(), 0.0);
        addSumPart(sums, frame.pixels);
        world.reduceSumToRoot(sums);
        if (world.rank() == 0) sumsToFrame(sums, frame);
        return;
    }
    }
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

} // namespace vots::dist
