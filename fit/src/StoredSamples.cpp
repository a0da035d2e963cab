// Reads any run of z planes of an uncompressed volume file by offset, decoding as the whole load does.
#include "StoredSamples.h"

#include "InputFile.h"
#include "SampleDecode.h"

#include <algorithm>

namespace vots::fit::detail {

namespace {

// Bytes [from, from + count) of the payload the pieces make up, one after the other, at `destination`.
void readPayloadRange(const std::vector<PayloadPiece>& pieces, std::uint64_t from, std::size_t count,
                      unsigned char* destination) {
    std::uint64_t pieceStart = 0; // where the piece begins in the payload
    for (const PayloadPiece& piece : pieces) {
        const std::uint64_t pieceEnd = pieceStart + piece.bytes;
        if (count > 0 && from < pieceEnd) {
            const std::uint64_t skip = from - pieceStart;
            const std::size_t take =
                static_cast<std::size_t>(std::min<std::uint64_t>(count, pieceEnd - from));
            readFileBytesInto(piece.file, piece.start + skip, take, destination);
            destination += take;
            from += take;
            count -= take;
        }
        pieceStart = pieceEnd;
    }
}

} // namespace

Volume readStoredPlanes(const std::string& path, const StoredSamples& stored, int first, int last,
                        SampleStorage storage) {
    Volume volume = gridOfPlanes(stored.grid, first, last);
    // The whole payload must be there, whichever planes are read: a short file is refused alike
    // by every reader of a slab of it.
    for (const PayloadPiece& piece : stored.pieces)
        checkFileHolds(piece.file, piece.start, piece.bytes);
    // A named range, not structured bindings: clang 14 (the fuzz preset's compiler) cannot capture those.
    const PayloadRange range = payloadRangeOf(stored, volume, first);
    const bool scaled = stored.slope != 0.0;
    // Scaled samples are not integers any more: only unscaled ones stay compact.
    readSamples(volume, range.count, stored.type, stored.bigEndian, scaled ? SampleStorage::Float : storage,
                [&](unsigned char* destination) {
                    readPayloadRange(stored.pieces, range.from, range.count * range.sampleBytes, destination);
                });
    if (scaled) applyScaling(path, volume.values, stored.slope, stored.inter);
    return volume;
}

Volume readStoredVolume(const std::string& path, const StoredSamples& stored, SampleStorage storage) {
    return readStoredPlanes(path, stored, 0, stored.grid.dims[2] - 1, storage);
}

} // namespace vots::fit::detail
