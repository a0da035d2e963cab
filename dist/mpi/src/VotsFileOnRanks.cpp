// writeVotSpaceOnRanks: the ranks' records written in place with MPI-IO, framed and published by rank 0.
#include "vots/dist/mpi/VotsFileOnRanks.h"

#include "vots/fit/AtomicFile.h"
#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"

#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace vots::dist {
namespace {

std::string mpiErrorText(int code) {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    return std::string(text, static_cast<std::size_t>(std::max(length, 0)));
}

/// Writes `bytes` at `offset` in pieces MPI's int counts hold; returns empty, or what failed.
std::string writeAt(MPI_File file, std::uint64_t offset, const std::vector<std::uint8_t>& bytes) {
    constexpr std::size_t PIECE = std::size_t{1} << 30;
    for (std::size_t done = 0; done < bytes.size();) {
        const std::size_t piece = std::min(PIECE, bytes.size() - done);
        MPI_Status status;
        const int code = MPI_File_write_at(file, static_cast<MPI_Offset>(offset + done), bytes.data() + done,
                                           static_cast<int>(piece), MPI_BYTE, &status);
        if (code != MPI_SUCCESS) return mpiErrorText(code);
        int written = 0;
        MPI_Get_count(&status, MPI_BYTE, &written);
        if (written != static_cast<int>(piece)) return "fewer bytes written than asked (is the disk full?)";
        done += piece;
    }
    return "";
}

} // namespace

void writeVotSpaceOnRanks(const MpiWorld& world, const std::string& path, const fit::VotSpace& mine) {
    // Validated as one process's writer validates the whole, before anything touches the disk.
    fit::VotRecords records;
    world.allOrNone([&] { records = fit::encodeVotRecords(mine); });
    const std::uint64_t before = world.sumBeforeRank(records.bytes.size());
    const std::vector<fit::VotRecordsPart> parts =
        world.gatherOnRoot(std::vector<fit::VotRecordsPart>{{records.crc, records.bytes.size()}});
    fit::VotSpaceFrame frame;
    std::string temporary;
    world.allOrNone([&] {
        if (world.rank() != 0) return;
        frame = fit::encodeVotSpaceFrame(mine, parts);
        temporary = fit::uniqueTemporaryPath(path);
    });
    temporary = world.broadcastFromRoot(temporary);
    const auto removeTemporary = [&] {
        if (world.rank() == 0) ::unlink(temporary.c_str());
    };

    MPI_File file = MPI_FILE_NULL; // files return their errors (MPI_ERRORS_RETURN is their default)
    const int opened = MPI_File_open(MPI_COMM_WORLD, temporary.c_str(),
                                     MPI_MODE_WRONLY | MPI_MODE_CREATE | MPI_MODE_EXCL, MPI_INFO_NULL, &file);
    try {
        world.allOrNone([&] {
            if (opened != MPI_SUCCESS)
                throw fit::InputError("cannot write '" + path + "': " + mpiErrorText(opened));
        });
    } catch (...) {
        removeTemporary();
        throw;
    }
    std::string problem = writeAt(file, fit::VOTS_HEADER_BYTES + before, records.bytes);
    if (world.rank() == 0 && problem.empty()) problem = writeAt(file, 0, frame.header);
    if (world.rank() == 0 && problem.empty()) problem = writeAt(file, frame.tailAt, frame.tail);
    // Collectives, on every rank whatever its writes did: every part on the disk before the rename.
    const int synced = MPI_File_sync(file);
    const int closed = MPI_File_close(&file);
    if (problem.empty() && synced != MPI_SUCCESS) problem = mpiErrorText(synced);
    if (problem.empty() && closed != MPI_SUCCESS) problem = mpiErrorText(closed);
    try {
        world.allOrNone([&] {
            if (!problem.empty()) throw std::runtime_error("cannot write '" + path + "': " + problem);
        });
    } catch (...) {
        removeTemporary();
        throw;
    }
    world.allOrNone([&] {
        if (world.rank() == 0) fit::publishTemporary(temporary, path);
    });
}

} // namespace vots::dist
