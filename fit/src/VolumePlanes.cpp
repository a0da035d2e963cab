// Runs of z planes: cut out of a loaded volume, or read alone (by offset, from a gzip stream, or a DICOM
// series' own slices).
#include "vots/fit/VolumePlanes.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"

#include "GzipPlanes.h"
#include "InputFile.h"
#include "StoredSamples.h"

#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace vots::fit {

Volume detail::gridOfPlanes(const Volume& volume, int first, int last) {
    if (first < 0 || last < first || last >= volume.dims[2])
        throw InputError("planes " + std::to_string(first) + ".." + std::to_string(last) +
                         " are not inside the volume's 0.." + std::to_string(volume.dims[2] - 1));
    Volume part;
    part.dims = {volume.dims[0], volume.dims[1], last - first + 1};
    part.spacing = volume.spacing;
    part.origin = volume.origin;
    if (first > 0) // plane 0 keeps the origin's bits (also a -0.0)
        for (int w = 0; w < 3; ++w)
            part.origin[w] += volume.patientAxes[2][w] * volume.spacing[2] * first;
    part.patientAxes = volume.patientAxes;
    part.orientationKnown = volume.orientationKnown;
    part.sourceType = volume.sourceType;
    part.name = volume.name;
    return part;
}

Volume gridOf(const Volume& volume) {
    return detail::gridOfPlanes(volume, 0, volume.dims[2] - 1);
}

Volume planesOf(const Volume& volume, int first, int last) {
    Volume part = detail::gridOfPlanes(volume, first, last);
    const std::size_t plane =
        static_cast<std::size_t>(volume.dims[0]) * static_cast<std::size_t>(volume.dims[1]);
    const auto begin = static_cast<std::ptrdiff_t>(plane * static_cast<std::size_t>(first));
    const auto end = static_cast<std::ptrdiff_t>(plane * (static_cast<std::size_t>(last) + 1));
    if (!volume.isCompact()) {
        part.values.assign(volume.values.begin() + begin, volume.values.begin() + end);
        return part;
    }
    std::visit(
        [&](const auto& held) {
            using Held = std::decay_t<decltype(held)>;
            if constexpr (!std::is_same_v<Held, std::monostate>)
                part.compact = Held(held.begin() + begin, held.begin() + end);
        },
        volume.compact);
    return part;
}

namespace {

// The layout of a file whose samples can be read by offset; nullopt for compressed payloads and DICOM.
std::optional<detail::StoredSamples> storedSamplesOf(const std::string& path,
                                                     const std::optional<RawLayout>& raw, int frame = 0) {
    const std::string extension = raw || isDicomFolder(path) ? std::string() : detail::volumeExtension(path);
    if (extension == ".nii" || extension == ".nii.gz") return detail::storedNiftiSamples(path, frame);
    if (extension == ".mgh" || extension == ".mgz") return detail::storedMghSamples(path, frame);
    detail::checkFrame(path, frame, 1);
    if (raw) return detail::storedRawSamples(path, *raw);
    if (isDicomFolder(path)) return std::nullopt;
    if (extension == ".nrrd" || extension == ".nhdr") return detail::storedNrrdSamples(path);
    if (extension == ".mhd" || extension == ".mha") return detail::storedMetaImageSamples(path);
    detail::throwUnknownVolumeFormat(path);
}

// The streams of a gzip NRRD, NIfTI or compressed MetaImage; nullopt for every other file (also an
// uncompressed one).
std::optional<detail::GzipSamples> gzipSamplesOf(const std::string& path, const std::optional<RawLayout>& raw,
                                                 int frame = 0) {
    if (raw || isDicomFolder(path)) return std::nullopt;
    const std::string extension = detail::volumeExtension(path);
    if (extension == ".nrrd" || extension == ".nhdr") return detail::gzipNrrdSamples(path);
    if (extension == ".nii" || extension == ".nii.gz") return detail::gzipNiftiSamples(path, frame);
    if (extension == ".mgh" || extension == ".mgz") return detail::gzipMghSamples(path, frame);
    if (extension == ".mhd" || extension == ".mha") return detail::gzipMetaImageSamples(path);
    return std::nullopt;
}

} // namespace

bool readsOnlyPlanes(const std::string& path, const std::optional<RawLayout>& raw) {
    return (!raw && isDicomFolder(path)) || storedSamplesOf(path, raw).has_value() ||
           gzipSamplesOf(path, raw).has_value();
}

PlanesOfGrid loadVolumePlanes(const std::string& path, int first, int last,
                              const std::optional<RawLayout>& raw, SampleStorage storage,
                              const std::string& dicomSeries, int frame) {
    if (!raw && isDicomFolder(path)) {
        PlanesOfGrid read;
        read.planes = loadDicomSeriesPlanes(path, first, last, read.whole, dicomSeries, storage, frame);
        return read;
    }
    if (auto stored = storedSamplesOf(path, raw, frame)) {
        Volume planes = detail::readStoredPlanes(path, *stored, first, last, storage);
        return {std::move(planes), std::move(stored->grid)};
    }
    if (auto stored = gzipSamplesOf(path, raw, frame)) {
        Volume planes = detail::readGzipPlanes(path, *stored, first, last, storage);
        return {std::move(planes), std::move(stored->grid)};
    }
    // What is neither stored by offset nor a gzip/zlib stream (an encoding the readers accept otherwise):
    // loaded whole and cut.
    const Volume whole = loadVolume(path, raw, storage, dicomSeries, frame);
    return {planesOf(whole, first, last), gridOf(whole)};
}

} // namespace vots::fit
