// The MPI world `vots` runs in: rank 0 of 1 unless mpirun started it, and the frame reductions.
#pragma once

#include <array>
#include <vector>

namespace vots::cli {

/// MPI is initialised only when the environment says a launcher started this process (Open MPI's
/// OMPI_COMM_WORLD_SIZE, or PMIx's PMIX_RANK); otherwise the world is rank 0 of 1 and no MPI call is
/// ever made, so `vots` without mpirun behaves exactly as a plain program. Finalised at exit.
class MpiWorld {
public:
    static MpiWorld& get();
    MpiWorld(const MpiWorld&) = delete;
    MpiWorld& operator=(const MpiWorld&) = delete;
    ~MpiWorld();

    int rank() const { return mRank; }
    int size() const { return mSize; }
    bool distributed() const { return mSize > 1; }

    /// Element-wise maximum (or minimum) of every rank's values onto rank 0's `values` (same length on
    /// every rank); the other ranks' vectors are left as they were.
    void reduceMaxToRoot(std::vector<float>& values) const;
    void reduceMinToRoot(std::vector<float>& values) const;
    /// [min over ranks of range[0], max over ranks of range[1]], on every rank.
    std::array<float, 2> unionOfRanges(std::array<float, 2> range) const;

private:
    MpiWorld();
    int mRank = 0;
    int mSize = 1;
    bool mInitialised = false;
};

} // namespace vots::cli
