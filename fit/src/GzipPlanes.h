// Private: runs of z planes of a gzip-compressed payload, decompressed as a stream and kept from the first.
#pragma once

#include "SampleFormat.h"

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// One data file's share of the payload, compressed: the stream starts at `start` in `file` and holds
/// `skip` bytes (NRRD's byte skip counts decompressed bytes) before the share's `bytes`. It runs to the
/// file's end, or over `packedBytes` (MetaImage's CompressedDataSize) when given.
struct GzipPiece {
    std::string file;
    std::uint64_t start = 0;
    std::uint64_t skip = 0;
    std::size_t bytes = 0;
    std::optional<std::uint64_t> packedBytes;
    bool endsStream = true; // false: more follows (later frames of a 4D file, MGH's trailing tags)
};

/// A volume file whose payload is gzip or zlib streams, header already checked: its format and the streams
/// that, one after the other, decompress to the payload.
struct GzipSamples : SampleFormat {
    std::vector<GzipPiece> pieces;
};

/// NRRD's header pass for gzip encoding, NIfTI's for a .nii.gz (its header read from the stream's start),
/// MetaImage's for CompressedData (a zlib stream); nullopt for an uncompressed payload (StoredSamples
/// reads that by offset).
std::optional<GzipSamples> gzipNrrdSamples(const std::string& path);
std::optional<GzipSamples> gzipNiftiSamples(const std::string& path, int frame = 0);
/// FreeSurfer's .mgz (MghReader.cpp); nullopt for an uncompressed .mgh.
std::optional<GzipSamples> gzipMghSamples(const std::string& path, int frame = 0);
std::optional<GzipSamples> gzipMetaImageSamples(const std::string& path);

/// Planes [first, last] (first <= last inside the grid), as cutting them out of the whole load gives them.
/// Each stream is decompressed from its start, the bytes before the planes are discarded as they come,
/// and it stops after the last plane, so the memory taken is the planes' bytes (and a chunk of
/// compressed input). A stream whose end is read must end there, as the whole load checks.
Volume readGzipPlanes(const std::string& path, const GzipSamples& stored, int first, int last,
                      SampleStorage storage);

/// The whole volume: readGzipPlanes of every plane.
Volume readGzipVolume(const std::string& path, const GzipSamples& stored, SampleStorage storage);

} // namespace vots::fit::detail
