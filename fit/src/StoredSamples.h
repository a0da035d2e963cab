// Private: where an uncompressed volume file keeps its samples, so any run of z planes is read by offset.
#pragma once

#include "SampleFormat.h"

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// One contiguous run of the payload (the samples as the file stores them) in one file.
struct PayloadPiece {
    std::string file;
    std::uint64_t start = 0; // byte offset of the run in `file`
    std::size_t bytes = 0;
};

/// A volume file whose payload lies uncompressed in one or more files, header already checked: its
/// format and the runs that, one after the other, make up the payload.
struct StoredSamples : SampleFormat {
    std::vector<PayloadPiece> pieces;
};

/// Each reader's header pass: the layout of an uncompressed file, or nullopt when its payload is
/// compressed (gzip, zlib), which cannot be entered at an offset. Throws the reader's InputError for a
/// malformed header or a file that does not hold exactly the payload the header describes.
std::optional<StoredSamples> storedNrrdSamples(const std::string& path);
/// `frame` picks one 3D volume of a 4D file (NIfTI, MGH); out of range is an InputError naming the count.
std::optional<StoredSamples> storedNiftiSamples(const std::string& path, int frame = 0);
std::optional<StoredSamples> storedMghSamples(const std::string& path, int frame = 0);
std::optional<StoredSamples> storedMetaImageSamples(const std::string& path);
StoredSamples storedRawSamples(const std::string& path, const RawLayout& layout);

/// The grid of planes [first, last] of `volume` without its samples: z size and origin moved to plane
/// `first`. Throws InputError unless 0 <= first <= last < dims z.
Volume gridOfPlanes(const Volume& volume, int first, int last);

/// Planes [first, last] along z (first <= last inside the grid) read from the file, only their bytes:
/// the same samples, grid and storage as cutting them out of the whole volume.
Volume readStoredPlanes(const std::string& path, const StoredSamples& stored, int first, int last,
                        SampleStorage storage);

/// The whole volume: readStoredPlanes of every plane.
Volume readStoredVolume(const std::string& path, const StoredSamples& stored, SampleStorage storage);

/// Applies NIfTI's scl_slope/scl_inter to float samples; throws when one leaves float range.
void applyScaling(const std::string& path, std::vector<float>& values, double slope, double inter);

} // namespace vots::fit::detail
