// The MPI world `vots` runs in: rank 0 of 1 unless mpirun started it, and the frame reductions.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace vots::dist {

/// Thrown on the ranks other than 0 when a step of MpiWorld::allOrNone failed on some rank: rank 0 reports
/// it, the others only end with its exit code.
class ReportedOnRank0 : public std::runtime_error {
public:
    explicit ReportedOnRank0(int exitCode) : std::runtime_error("reported on rank 0"), mExitCode(exitCode) {}
    int exitCode() const { return mExitCode; }

private:
    int mExitCode;
};

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
    /// True when mpirun started this process, even as the only rank.
    bool launched() const { return mInitialised; }
    /// A peer has died: MPI_Finalize would wait for ever on a message still going to it (seen under
    /// `vots serve`: a heartbeat to a killed rank 0), so the process ends without it; mpirun takes the
    /// exit as the rank's end.
    void leaveUnfinalized() { mInitialised = false; }

    /// Element-wise maximum (or minimum) of every rank's values onto rank 0's `values` (same length on
    /// every rank); the other ranks' vectors are left as they were.
    void reduceMaxToRoot(std::vector<float>& values) const;
    void reduceMinToRoot(std::vector<float>& values) const;
    /// Element-wise sum of every rank's values onto rank 0's `values`, likewise. Open MPI sums in the same
    /// order for the same count and ranks, so the same inputs give the same bits.
    void reduceSumToRoot(std::vector<double>& values) const;
    /// [min over ranks of range[0], max over ranks of range[1]], on every rank.
    std::array<float, 2> unionOfRanges(std::array<float, 2> range) const;
    /// Element-wise sum (or the maximum) over the ranks, on every rank.
    std::vector<std::uint64_t> sumOverRanks(std::vector<std::uint64_t> values) const;
    double sumOverRanks(double value) const;
    double maxOverRanks(double value) const;
    /// The sum of `value` over the ranks before this one (0 on rank 0), on every rank.
    std::uint64_t sumBeforeRank(std::uint64_t value) const;
    /// Rank 0's `text`, on every rank.
    std::string broadcastFromRoot(std::string text) const;

    /// Runs `step` on every rank, then agrees on how it went, so that no rank waits in a later
    /// collective for one that has left: when it threw on any rank, rank 0 throws the first failing
    /// rank's error (prefixed "rank R: " when R is not 0, as failureOf its kind) and every other rank
    /// throws ReportedOnRank0 with its exit code (exitCodeOf), which main() turns into a silent exit.
    /// Steps must not call collectives themselves. Without mpirun: just `step()`.
    void allOrNone(const std::function<void()>& step) const;

    /// Every rank's record, in rank order, on every rank.
    template <typename Record> std::vector<Record> gatherOnEveryRank(const Record& mine) const {
        static_assert(std::is_trivially_copyable_v<Record>, "records travel as their bytes");
        std::vector<Record> all(static_cast<std::size_t>(mSize));
        if (!distributed()) {
            all[0] = mine;
            return all;
        }
        gatherBytesOnEveryRank(&mine, sizeof(Record), all.data());
        return all;
    }

    /// Every rank's records, concatenated in rank order, on rank 0; empty on the other ranks.
    template <typename Record> std::vector<Record> gatherOnRoot(const std::vector<Record>& mine) const {
        static_assert(std::is_trivially_copyable_v<Record>, "records travel as their bytes");
        if (!launched()) return mine;
        std::vector<Record> all;
        gatherRecords(mine.data(), mine.size(), sizeof(Record), [&](std::size_t count) {
            all.resize(count);
            return static_cast<void*>(all.data());
        });
        return all;
    }

private:
    MpiWorld();
    void gatherBytesOnEveryRank(const void* mine, std::size_t bytes, void* all) const;
    /// gatherOnRoot's bytes: `allocate(total records)` gives rank 0 the destination.
    void gatherRecords(const void* mine, std::size_t count, std::size_t recordBytes,
                       const std::function<void*(std::size_t)>& allocate) const;
    int mRank = 0;
    int mSize = 1;
    bool mInitialised = false;
};

} // namespace vots::dist
