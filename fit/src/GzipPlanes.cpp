// Runs of z planes of a gzip payload: every stream inflated from its start, kept only where the planes are.
#include "GzipPlanes.h"

#include "Gzip.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

#include <algorithm>

namespace vots::fit::detail {

Volume readGzipPlanes(const std::string& path, const GzipSamples& stored, int first, int last,
                      SampleStorage storage) {
    Volume volume = gridOfPlanes(stored.grid, first, last);
    const auto [count, sampleBytes, from] = payloadRangeOf(stored, volume, first);
    const std::uint64_t to = from + static_cast<std::uint64_t>(count) * sampleBytes;
    // Grown with the data actually decompressed (Inflater::readExactly), not the header's claim.
    std::vector<unsigned char> payload;
    std::uint64_t pieceStart = 0; // where the piece's share begins in the payload
    for (const GzipPiece& piece : stored.pieces) {
        const std::uint64_t pieceEnd = pieceStart + piece.bytes;
        if (from < pieceEnd && to > pieceStart) {
            const std::uint64_t begin = std::max(from, pieceStart);
            const std::uint64_t end = std::min(to, pieceEnd);
            Inflater inflater(piece.file, piece.file, piece.start, piece.packedBytes);
            inflater.skip(static_cast<std::size_t>(piece.skip + (begin - pieceStart)));
            std::vector<unsigned char> part = inflater.readExactly(static_cast<std::size_t>(end - begin));
            // The reader of a stream's last bytes checks that it ends there; under mpirun every stream's
            // end is some rank's, so a file the whole load refuses is refused by the ranks together.
            if (end == pieceEnd && piece.endsStream) inflater.expectEnd();
            if (payload.empty())
                payload = std::move(part);
            else
                payload.insert(payload.end(), part.begin(), part.end());
        }
        pieceStart = pieceEnd;
    }
    // Scaled samples are not integers any more: only unscaled ones stay compact.
    const bool scaled = stored.slope != 0.0;
    storeSamples(volume, payload.data(), count, stored.type, stored.bigEndian,
                 scaled ? SampleStorage::Float : storage);
    if (scaled) applyScaling(path, volume.values, stored.slope, stored.inter);
    return volume;
}

Volume readGzipVolume(const std::string& path, const GzipSamples& stored, SampleStorage storage) {
    return readGzipPlanes(path, stored, 0, stored.grid.dims[2] - 1, storage);
}

} // namespace vots::fit::detail
