// The MPI world `vots` runs in: rank 0 of 1 unless mpirun started it, and the frame reductions.
#include "vots/dist/mpi/MpiWorld.h"

#include "vots/dist/Failure.h"

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

namespace vots::dist {

MpiWorld& MpiWorld::get() {
    static MpiWorld world;
    return world;
}

MpiWorld::MpiWorld() {
    if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK")) return;
    int provided = 0;
    // One thread at a time calls MPI: the main thread, or under `vots serve` the render thread while the
    // main thread waits for a signal (and calls MPI again only once that thread is joined).
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    mInitialised = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
    MPI_Comm_size(MPI_COMM_WORLD, &mSize);
}

MpiWorld::~MpiWorld() {
    if (mInitialised) MPI_Finalize();
}

namespace {
template <typename Value> MPI_Datatype mpiTypeOf();
template <> MPI_Datatype mpiTypeOf<float>() {
    return MPI_FLOAT;
}
template <> MPI_Datatype mpiTypeOf<double>() {
    return MPI_DOUBLE;
}

template <typename Value> void reduceToRoot(std::vector<Value>& values, MPI_Op op, int rank) {
    const int count = static_cast<int>(values.size());
    if (rank == 0)
        MPI_Reduce(MPI_IN_PLACE, values.data(), count, mpiTypeOf<Value>(), op, 0, MPI_COMM_WORLD);
    else
        MPI_Reduce(values.data(), nullptr, count, mpiTypeOf<Value>(), op, 0, MPI_COMM_WORLD);
}
} // namespace

void MpiWorld::reduceMaxToRoot(std::vector<float>& values) const {
    if (distributed()) reduceToRoot(values, MPI_MAX, mRank);
}

void MpiWorld::reduceMinToRoot(std::vector<float>& values) const {
    if (distributed()) reduceToRoot(values, MPI_MIN, mRank);
}

void MpiWorld::reduceSumToRoot(std::vector<double>& values) const {
    if (distributed()) reduceToRoot(values, MPI_SUM, mRank);
}

std::array<float, 2> MpiWorld::unionOfRanges(std::array<float, 2> range) const {
    if (!distributed()) return range;
    float lo = range[0], hi = range[1];
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_FLOAT, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_FLOAT, MPI_MAX, MPI_COMM_WORLD);
    return {lo, hi};
}

std::vector<std::uint64_t> MpiWorld::sumOverRanks(std::vector<std::uint64_t> values) const {
    if (distributed())
        MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, MPI_SUM,
                      MPI_COMM_WORLD);
    return values;
}

double MpiWorld::sumOverRanks(double value) const {
    if (distributed()) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    return value;
}

double MpiWorld::maxOverRanks(double value) const {
    if (distributed()) MPI_Allreduce(MPI_IN_PLACE, &value, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return value;
}

std::uint64_t MpiWorld::sumBeforeRank(std::uint64_t value) const {
    std::uint64_t before = 0;
    if (distributed()) MPI_Exscan(&value, &before, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    return mRank == 0 ? 0 : before; // MPI_Exscan leaves rank 0's result undefined
}

std::string MpiWorld::broadcastFromRoot(std::string text) const {
    if (!distributed()) return text;
    std::uint64_t size = text.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    text.resize(static_cast<std::size_t>(size));
    MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
    return text;
}

void MpiWorld::allOrNone(const std::function<void()>& step) const {
    if (!distributed()) return step();
    int code = 0; // exitCodeOf the failure's kind; 0: none
    std::int32_t kind = 0;
    std::string message;
    std::exception_ptr failure;
    try {
        step();
    } catch (...) {
        failure = std::current_exception();
        kind = static_cast<std::int32_t>(failureKindOf(failure));
        code = exitCodeOf(static_cast<FailureKind>(kind));
        message = failureTextOf(failure);
    }
    // The lowest failing rank, if any: MINLOC over (0 failed, 1 fine).
    struct {
        int fine;
        int rank;
    } mine{code == 0 ? 1 : 0, mRank}, first{};
    MPI_Allreduce(&mine, &first, 1, MPI_2INT, MPI_MINLOC, MPI_COMM_WORLD);
    if (first.fine == 1) return;
    int header[3] = {code, kind, static_cast<int>(message.size())};
    MPI_Bcast(header, 3, MPI_INT, first.rank, MPI_COMM_WORLD);
    message.resize(static_cast<std::size_t>(header[2]));
    MPI_Bcast(message.data(), header[2], MPI_CHAR, first.rank, MPI_COMM_WORLD);
    if (mRank != 0) throw ReportedOnRank0(header[0]); // rank 0 reports it
    if (first.rank == 0) std::rethrow_exception(failure);
    std::rethrow_exception(
        failureOf(failureKindFromWire(header[1]), "rank " + std::to_string(first.rank) + ": " + message));
}

void MpiWorld::gatherBytesOnEveryRank(const void* mine, std::size_t bytes, void* all) const {
    MPI_Allgather(mine, static_cast<int>(bytes), MPI_BYTE, all, static_cast<int>(bytes), MPI_BYTE,
                  MPI_COMM_WORLD);
}

void MpiWorld::gatherRecords(const void* mine, std::size_t count, std::size_t recordBytes,
                             const std::function<void*(std::size_t)>& allocate) const {
    const std::uint64_t myCount = count;
    std::vector<std::uint64_t> counts(mRank == 0 ? static_cast<std::size_t>(mSize) : 0);
    MPI_Gather(&myCount, 1, MPI_UINT64_T, counts.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    // Rank 0 alone knows the total and takes the memory: it tells every rank whether the gather goes on,
    // so a failure there leaves no rank waiting in MPI_Gatherv.
    std::vector<int> intCounts, offsets;
    void* all = nullptr;
    int problem = 0; // 1: more than MPI's int counts hold, 2: out of memory
    if (mRank == 0) {
        std::uint64_t total = 0;
        for (const std::uint64_t c : counts) {
            offsets.push_back(static_cast<int>(std::min<std::uint64_t>(total, INT_MAX)));
            intCounts.push_back(static_cast<int>(std::min<std::uint64_t>(c, INT_MAX)));
            total += c;
        }
        if (total > INT_MAX) {
            problem = 1;
        } else {
            try {
                all = allocate(static_cast<std::size_t>(total));
            } catch (const std::bad_alloc&) {
                problem = 2;
            }
        }
    }
    MPI_Bcast(&problem, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (problem == 1) throw std::runtime_error("more than 2^31 records to gather over the ranks");
    if (problem == 2) throw std::bad_alloc();
    // Counts in records of one derived type, so a gather is not limited to 2 GB of bytes.
    MPI_Datatype record;
    MPI_Type_contiguous(static_cast<int>(recordBytes), MPI_BYTE, &record);
    MPI_Type_commit(&record);
    MPI_Gatherv(mine, static_cast<int>(count), record, all, intCounts.data(), offsets.data(), record, 0,
                MPI_COMM_WORLD);
    MPI_Type_free(&record);
}

} // namespace vots::dist
