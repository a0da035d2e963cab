// The MPI world `vots` runs in: rank 0 of 1 unless mpirun started it, and the frame reductions.
#include "MpiWorld.h"

#include <mpi.h>

#include <cstdlib>

namespace vots::cli {

MpiWorld& MpiWorld::get() {
    static MpiWorld world;
    return world;
}

MpiWorld::MpiWorld() {
    if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK")) return;
    int provided = 0;
    // One thread calls MPI (the main thread); the renderer's own threads never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    mInitialised = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
    MPI_Comm_size(MPI_COMM_WORLD, &mSize);
}

MpiWorld::~MpiWorld() {
    if (mInitialised) MPI_Finalize();
}

namespace {
void reduceToRoot(std::vector<float>& values, MPI_Op op, int rank) {
    const int count = static_cast<int>(values.size());
    if (rank == 0)
        MPI_Reduce(MPI_IN_PLACE, values.data(), count, MPI_FLOAT, op, 0, MPI_COMM_WORLD);
    else
        MPI_Reduce(values.data(), nullptr, count, MPI_FLOAT, op, 0, MPI_COMM_WORLD);
}
} // namespace

void MpiWorld::reduceMaxToRoot(std::vector<float>& values) const {
    if (distributed()) reduceToRoot(values, MPI_MAX, mRank);
}

void MpiWorld::reduceMinToRoot(std::vector<float>& values) const {
    if (distributed()) reduceToRoot(values, MPI_MIN, mRank);
}

std::array<float, 2> MpiWorld::unionOfRanges(std::array<float, 2> range) const {
    if (!distributed()) return range;
    float lo = range[0], hi = range[1];
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_FLOAT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_FLOAT, MPI_MAX, MPI_COMM_WORLD);
    return {lo, hi};
}

} // namespace vots::cli
