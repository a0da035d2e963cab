// Reads single-file NIfTI-1 and NIfTI-2 volumes (.nii, .nii.gz) of either byte order, one frame of a 4D
// file at a time; no .hdr/.img pairs. The header's rules live in NiftiHeader.cpp.
#include "vots/fit/VolumeLoad.h"

#include "Gzip.h"
#include "GzipPlanes.h"
#include "InputFile.h"
#include "NiftiHeader.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace vots::fit {

namespace {

using namespace detail;

SampleFormat formatOf(const std::string& path, const NiftiInfo& info) {
    return {gridOfHeader(path, info), info.type, info.bigEndian, info.slope, info.inter};
}

StoredSamples storedPlain(const std::string& path, std::uint64_t fileSize, int frame) {
    if (fileSize < NIFTI1_HEADER_BYTES)
        throwInputError(path, "too short for a NIfTI header (" + std::to_string(fileSize) + " bytes)");
    const std::vector<unsigned char> first = readFileBytes(path, 0, 4);
    const std::vector<unsigned char> header = readFileBytes(path, 0, niftiHeaderBytes(path, first.data()));
    const NiftiInfo info = parseNiftiHeader(path, header.data());
    const std::uint64_t expected =
        info.voxOffset + info.frames * static_cast<std::uint64_t>(info.shape.bytes);
    if (fileSize > expected)
        throwInputError(path, "holds " + std::to_string(fileSize) + " bytes but the header describes " +
                                  std::to_string(expected) + " (wrong dims or datatype?)");
    // The whole payload must be there, whichever frame is read: a short file is refused alike for all.
    checkFileHolds(path, info.voxOffset, static_cast<std::size_t>(expected - info.voxOffset));
    return {formatOf(path, info), {{path, frameOffset(path, info, frame), info.shape.bytes}}};
}

} // namespace

std::optional<StoredSamples> detail::storedNiftiSamples(const std::string& path, int frame) {
    if (isGzipFile(path)) return std::nullopt;
    return storedPlain(path, regularFileSize(path), frame);
}

std::optional<GzipSamples> detail::gzipNiftiSamples(const std::string& path, int frame) {
    if (!isGzipFile(path)) return std::nullopt;
    // The header is the stream's first bytes; the samples start at vox_offset of the decompressed file.
    Inflater inflater(path, path, 0);
    std::vector<unsigned char> header = inflater.readExactly(4);
    const std::vector<unsigned char> rest = inflater.readExactly(niftiHeaderBytes(path, header.data()) - 4);
    header.insert(header.end(), rest.begin(), rest.end());
    const NiftiInfo info = parseNiftiHeader(path, header.data());
    const bool lastFrame = static_cast<std::uint64_t>(frame) + 1 == info.frames;
    return GzipSamples{
        formatOf(path, info),
        {{path, 0, frameOffset(path, info, frame), info.shape.bytes, std::nullopt, lastFrame}}};
}

void detail::applyScaling(const std::string& path, std::vector<float>& values, double slope, double inter) {
    std::size_t bad = 0;
    for (float& v : values) {
        if (!std::isfinite(v)) continue; // no data stays no data
        const double scaled = v * slope + inter;
        const bool ok = std::fabs(scaled) <= std::numeric_limits<float>::max();
        bad += ok ? 0 : 1;
        v = ok ? static_cast<float>(scaled) : 0.0f;
    }
    if (bad > 0)
        throwInputError(path, std::to_string(bad) + " samples leave float range after scl_slope/scl_inter");
}

Volume loadNifti(const std::string& path, SampleStorage storage, int frame) {
    if (auto stored = storedNiftiSamples(path, frame)) return readStoredVolume(path, *stored, storage);
    return readGzipVolume(path, *gzipNiftiSamples(path, frame), storage);
}

} // namespace vots::fit
