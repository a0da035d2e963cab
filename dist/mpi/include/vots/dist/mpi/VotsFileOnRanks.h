// One .vots file written by every rank under mpirun with MPI-IO: each rank its own Vots' records at their
// offset, rank 0 the header, the meta block and the CRC around them, so no rank holds another's Vots.
#pragma once

#include "vots/dist/mpi/MpiWorld.h"

#include "vots/fit/VotSpace.h"

#include <string>

namespace vots::dist {

/// A collective. `mine`: this rank's Vots, in the whole grid, with the file's header fields (the same on
/// every rank); rank 0's metaJson is the file's meta block (the others' are not written). The ranks write
/// a temporary that rank 0 renames over `path` once every part is synced: a failure on any rank leaves
/// the old file (or none), never a mix, and throws on every rank as MpiWorld::allOrNone does.
void writeVotSpaceOnRanks(const MpiWorld& world, const std::string& path, const fit::VotSpace& mine);

} // namespace vots::dist
