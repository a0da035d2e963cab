// `vots render` under mpirun: the ranks' float frames composited onto rank 0 with MPI collectives, by the
// composite table's operation (vots/dist/CompositeOp.h).
#pragma once

#include "vots/dist/CompositeOp.h"
#include "vots/dist/mpi/MpiWorld.h"

#include "vots/render/Image.h"

#include <chrono>
#include <optional>

namespace vots::dist {

/// Composites the ranks' frames of one projection onto rank 0 (elsewhere `frame` is left undefined) by
/// `op`: for WeightedMean each rank's `lengths` (VotRenderer::rayLengths in its cells) must be given.
/// A collective.
void compositeOnRoot(const MpiWorld& world, CompositeOp op, render::FloatImage& frame,
                     const std::optional<render::FloatImage>& lengths);

/// `vots render --times`: milliseconds since `start`, the slowest rank's (every rank must call it: it
/// waits for them all, so the next step's time is its own).
double slowestRankMillisSince(const MpiWorld& world, std::chrono::steady_clock::time_point start);
/// Rank 0 prints the frame's split on stderr: "vots render: N rank(s), render R ms, composite C ms".
void reportFrameTimes(const MpiWorld& world, double renderMs, double compositeMs);

} // namespace vots::dist
