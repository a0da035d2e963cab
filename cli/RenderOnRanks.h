// `vots render` under mpirun: each rank draws its z cells (its Vots, or its planes with the exact grid) and
// rank 0 writes the composited frame or turntable (docs/DESIGN.md, "Across hosts").
#pragma once

#include "RenderArgs.h"

#include "vots/dist/mpi/MpiWorld.h"

namespace vots::cli {

/// Runs `vots render` on every rank of `world`. A failure on any rank (bad input, no EGL context, a
/// frame that cannot be written) ends every rank with its exit code; rank 0 prints the message.
void runRenderOnRanks(const dist::MpiWorld& world, const RenderArgs& a);

} // namespace vots::cli
