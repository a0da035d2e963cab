// Reads FreeSurfer MGH volumes (.mgh, and .mgz: the same gzip-compressed), one frame of a 4D file at a time.
#include "vots/fit/VolumeLoad.h"

#include "Gzip.h"
#include "GzipPlanes.h"
#include "InputFile.h"
#include "MghHeader.h"
#include "StoredSamples.h"

#include <cstdint>
#include <optional>

namespace vots::fit {

namespace {

using namespace detail;

std::uint64_t frameOffset(const std::string& path, const MghInfo& info, int frame) {
    checkFrame(path, frame, info.frames);
    return MGH_HEADER_BYTES + static_cast<std::uint64_t>(frame) * info.shape.bytes;
}

// MGH stores big-endian, unscaled.
SampleFormat formatOf(const std::string& path, const MghInfo& info) {
    return {gridOfHeader(path, info), info.type, true, 0.0, 0.0};
}

StoredSamples storedPlain(const std::string& path, int frame) {
    const std::vector<unsigned char> header = readFileBytes(path, 0, MGH_HEADER_BYTES);
    const MghInfo info = parseMghHeader(path, header.data());
    // Every frame must be there, whichever is read (optional scan parameters and tags may follow).
    checkFileHolds(path, MGH_HEADER_BYTES, static_cast<std::size_t>(info.frames * info.shape.bytes));
    return {formatOf(path, info), {{path, frameOffset(path, info, frame), info.shape.bytes}}};
}

} // namespace

std::optional<StoredSamples> detail::storedMghSamples(const std::string& path, int frame) {
    if (isGzipFile(path)) return std::nullopt;
    return storedPlain(path, frame);
}

std::optional<GzipSamples> detail::gzipMghSamples(const std::string& path, int frame) {
    if (!isGzipFile(path)) return std::nullopt;
    Inflater inflater(path, path, 0);
    const std::vector<unsigned char> header = inflater.readExactly(MGH_HEADER_BYTES);
    const MghInfo info = parseMghHeader(path, header.data());
    // The stream goes on after the samples (scan parameters, tags): its end is not checked.
    return GzipSamples{formatOf(path, info),
                       {{path, 0, frameOffset(path, info, frame), info.shape.bytes, std::nullopt, false}}};
}

Volume loadMgh(const std::string& path, SampleStorage storage, int frame) {
    if (auto stored = storedMghSamples(path, frame)) return readStoredVolume(path, *stored, storage);
    return readGzipVolume(path, *gzipMghSamples(path, frame), storage);
}

} // namespace vots::fit
