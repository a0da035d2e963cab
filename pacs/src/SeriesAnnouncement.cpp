// What a series is before it is retrieved: its instances and image size from QIDO-RS and its metadata.
#include "DicomJson.h"
#include "DicomWebConnection.h"
#include "SeriesResources.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/pacs/SeriesRetrieve.h"

#include <utility>

namespace vots::pacs {
namespace {

/// The type fit's DICOM reader gives these samples.
fit::ScalarType announcedType(const nlohmann::json& instance) {
    double bitsStored = dicomNumber(instance, "00280101").value_or(16.0);
    if (!(bitsStored >= 1 && bitsStored <= 32)) bitsStored = 16; // the reader checks the files' own
    return fit::dicomSampleType(
        static_cast<int>(bitsStored), dicomNumber(instance, "00280103").value_or(0.0) == 1.0,
        dicomNumber(instance, "00281053").value_or(1.0), dicomNumber(instance, "00281052").value_or(0.0));
}

/// Whether an instance's metadata holds its image attributes: Orthanc's "SeriesMetadata": "Extrapolate"
/// answers main tags alone (no SOPClassUID, no Rows), "Full" and other servers everything.
bool hasFullMetadata(const nlohmann::json& instance) {
    return !dicomString(instance, "00080016").empty();
}

/// Rows and Columns of an instance whose full metadata is at hand; throws for one that is not an image.
std::pair<int, int> imageSizeOf(const nlohmann::json& instance, const DicomWebSeries& series,
                                const std::string& sop) {
    const auto r = dicomNumber(instance, "00280010"), c = dicomNumber(instance, "00280011");
    if (!r || !c || *r <= 0 || *c <= 0)
        throw PacsError(PacsFailure::NotImages, series.describe() + ": instance " + sop +
                                                    " is not an image (SOP class " +
                                                    dicomString(instance, "00080016") +
                                                    ", no Rows and Columns); a volume needs images only");
    return {static_cast<int>(*r), static_cast<int>(*c)};
}

} // namespace

SeriesAnnouncement announceSeries(DicomWebConnection& connection, const DicomWebSeries& series) {
    const std::string unknown = series.describe() + ": no such series on the PACS";
    const nlohmann::json found =
        connection.getJson(seriesSearchResource(series) + "&includefield=00201209", "the series search");
    if (!found.is_array() || found.empty()) throw PacsError(PacsFailure::NotFound, unknown);
    const nlohmann::json metadata =
        connection.getJson(seriesResource(series) + "/metadata", "the series' metadata");
    if (!metadata.is_array() || metadata.empty())
        throw PacsError(PacsFailure::NotFound, unknown + " (it has no instances)");

    SeriesAnnouncement a;
    std::pair<int, int> size{0, 0};
    for (const nlohmann::json& instance : metadata) {
        const std::string sop = dicomString(instance, "00080018");
        if (sop.empty())
            throw PacsError(PacsFailure::Malformed,
                            series.describe() + ": an instance's metadata has no SOPInstanceUID");
        a.sopInstanceUids.push_back(sop);
        if (!hasFullMetadata(instance)) continue; // the folder reader checks what the metadata leaves out
        const std::pair<int, int> its = imageSizeOf(instance, series, sop);
        if (size.first == 0) {
            size = its;
            a.grid.sourceType = announcedType(instance);
        } else if (its != size) {
            throw PacsError(PacsFailure::NotImages,
                            series.describe() + ": mixed image sizes in the series (" +
                                std::to_string(size.second) + "x" + std::to_string(size.first) + " and " +
                                std::to_string(its.second) + "x" + std::to_string(its.first) + ")");
        }
    }
    if (size.first == 0) {
        // Abbreviated series metadata: the first instance's own metadata sizes the grid.
        const nlohmann::json first = connection.getJson(seriesResource(series) + "/instances/" +
                                                            a.sopInstanceUids.front() + "/metadata",
                                                        "an instance's metadata");
        if (!first.is_array() || first.empty())
            throw PacsError(PacsFailure::Malformed,
                            series.describe() + ": the first instance's metadata is empty");
        size = imageSizeOf(first.front(), series, a.sopInstanceUids.front());
        a.grid.sourceType = announcedType(first.front());
    }
    a.instanceCount = static_cast<int>(a.sopInstanceUids.size());
    a.grid.dims = {static_cast<std::uint64_t>(size.second), static_cast<std::uint64_t>(size.first),
                   static_cast<std::uint64_t>(a.instanceCount)};
    return a;
}

SeriesAnnouncement announceSeries(const DicomWebSeries& series, const DicomWebAccess& access) {
    DicomWebConnection connection(series.endpoint, access);
    return announceSeries(connection, series);
}

} // namespace vots::pacs
