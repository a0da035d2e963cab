// Vot-Space file version 1 (docs/DESIGN.md §8): exact byte layout, CRC-32, atomic write.
#pragma once

#include "vots/fit/VotSpace.h"

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace vots::fit {

/// The first 4 bytes of every Vot-Space file: what tells a .vots file from a volume.
inline constexpr std::string_view VOTS_MAGIC = "VOTS";
inline constexpr std::uint32_t VOTS_FILE_VERSION = 1;
inline constexpr std::size_t VOTS_HEADER_BYTES = 128;
inline constexpr std::size_t VOTS_RECORD_BYTES = 120;

/// Serialises to the exact v1 byte layout (header, records, meta JSON, CRC-32).
std::vector<std::uint8_t> encodeVotSpace(const VotSpace& space);
/// Parses and validates v1 bytes; throws InputError naming the first problem found
/// (magic, version, header size, length/count mismatch, CRC, box outside grid, lo >= hi, non-finite).
/// The fields a file keeps in its JSON meta block (patientAxes, orientationKnown, backgroundFill) stay
/// at their defaults: fit reads no JSON. Readers call meta::decodeVotSpace (vots/meta/VotSpaceRead.h),
/// which restores them.
VotSpace decodeVotSpaceWithoutMeta(const std::uint8_t* data, std::size_t size);

/// A file that several processes write (`mpirun vots fit`): each encodes the records of its own Vots
/// (encodeVotRecords), one process the frame around them (encodeVotSpaceFrame), and the bytes at their
/// offsets are those encodeVotSpace gives the whole Vot-Space, its CRC-32 chained from the parts'.
struct VotRecords {
    std::vector<std::uint8_t> bytes; // VOTS_RECORD_BYTES per Vot, in the space's order
    std::uint32_t crc = 0;           // CRC-32 (zlib) of bytes
};
/// One process's records as the frame's writer learns of them: their CRC and length.
struct VotRecordsPart {
    std::uint32_t crc = 0;
    std::uint64_t bytes = 0;
};
/// The header (at offset 0) and the meta block with the closing CRC (at tailAt) of a file; the parts'
/// records go between, the first at VOTS_HEADER_BYTES and each next one after the one before.
struct VotSpaceFrame {
    std::vector<std::uint8_t> header;
    std::vector<std::uint8_t> tail;
    std::uint64_t tailAt = 0;
};
/// The records of `space`'s Vots, validated as encodeVotSpace validates them (the header fields too: a
/// part's degree must not be below its coefficients'). Throws InputError.
VotRecords encodeVotRecords(const VotSpace& space);
/// The frame of a file with `space`'s header fields and meta block around `parts` in file order (their
/// counts summed; `space.vots` is not looked at). Throws InputError for invalid header fields.
VotSpaceFrame encodeVotSpaceFrame(const VotSpace& space, const std::vector<VotRecordsPart>& parts);

/// Writes the file atomically (writeFileAtomically, AtomicFile.h): a crash never leaves a half-written file
/// under the real name. Throws InputError when the folder is not writable. betweenChunks, when given, runs
/// between 1 MiB pieces of the write. A file several processes write (`mpirun vots fit`) goes through
/// uniqueTemporaryPath and publishTemporary (AtomicFile.h) instead.
void writeVotSpaceFile(const std::string& path, const VotSpace& space,
                       const std::function<void()>& betweenChunks = {});
/// Reads and validates a file as decodeVotSpaceWithoutMeta does; throws InputError with the path in the
/// message. Readers call meta::readVotSpaceFile (vots/meta/VotSpaceRead.h).
VotSpace readVotSpaceFileWithoutMeta(const std::string& path);

} // namespace vots::fit
