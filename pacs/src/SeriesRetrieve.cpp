// A series from a DICOMweb service into a spool folder: one streamed series request, per-instance fallback.
#include "vots/pacs/SeriesRetrieve.h"

#include "CancelWatch.h"
#include "DicomWebConnection.h"
#include "InstanceSpool.h"
#include "SeriesResources.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"

#include <gdcmReader.h>

#include <algorithm>
#include <set>
#include <thread>

namespace vots::pacs {
namespace {

/// One multipart GET into the spool; empty when every part of a complete answer is in, else why not.
std::string retrieveInto(DicomWebConnection& connection, const std::string& resource, InstanceSpool& spool) {
    SpoolStream stream(spool);
    std::string failure;
    const int status = connection.getStream(
        resource, DICOM_MULTIPART_ACCEPT, [&](const std::string& type) { return stream.begin(type); },
        [&](const char* data, std::size_t size) { return stream.receive(data, size); }, failure);
    if (!stream.problem().empty()) return stream.problem();
    if (status != 200) return failure.empty() ? connection.statusProblem(status, "the request") : failure;
    if (!failure.empty()) {
        stream.finish(); // removes a half-written part
        return failure;
    }
    return stream.finish() ? std::string() : stream.problem();
}

/// The SOPInstanceUID of a received instance, read from its header alone; empty when unreadable.
std::string sopInstanceUidOf(const std::string& path) {
    gdcm::Reader reader;
    reader.SetFileName(path.c_str());
    if (!reader.ReadUpToTag(gdcm::Tag(0x0008, 0x0019))) return {};
    const gdcm::DataSet& dataset = reader.GetFile().GetDataSet();
    const gdcm::Tag sopTag(0x0008, 0x0018);
    if (!dataset.FindDataElement(sopTag)) return {};
    const gdcm::ByteValue* value = dataset.GetDataElement(sopTag).GetByteValue();
    if (!value) return {};
    std::string uid(value->GetPointer(), value->GetLength());
    while (!uid.empty() && (uid.back() == '\0' || uid.back() == ' '))
        uid.pop_back();
    return uid;
}

/// The instances the spool lacks, in the series' order.
std::vector<std::string> missingInstances(const SeriesAnnouncement& announced, const InstanceSpool& spool) {
    std::set<std::string> received;
    for (const std::string& path : spool.completedFiles())
        received.insert(sopInstanceUidOf(path));
    std::vector<std::string> missing;
    for (const std::string& sop : announced.sopInstanceUids)
        if (!received.count(sop)) missing.push_back(sop);
    return missing;
}

/// Fetches `missing` one request each, `inFlight` at a time; empty, or the first failure.
std::string retrieveEach(const DicomWebSeries& series, const DicomWebAccess& access,
                         const std::vector<std::string>& missing, InstanceSpool& spool, int inFlight,
                         CancelWatch& watch) {
    std::atomic<std::size_t> next{0};
    std::mutex failureMutex;
    std::string failure;
    const auto failed = [&] {
        std::lock_guard lock(failureMutex);
        return !failure.empty();
    };
    const auto worker = [&] {
        try {
            DicomWebConnection connection(series.endpoint, access);
            const WatchedConnection watched(watch, connection);
            for (std::size_t i = next++; i < missing.size() && !failed(); i = next++) {
                const std::string problem =
                    retrieveInto(connection, seriesResource(series) + "/instances/" + missing[i], spool);
                if (!problem.empty()) {
                    std::lock_guard lock(failureMutex);
                    if (failure.empty()) failure = "instance " + missing[i] + ": " + problem;
                }
            }
        } catch (const std::exception& e) {
            std::lock_guard lock(failureMutex);
            if (failure.empty()) failure = e.what();
        }
    };
    const int threads = std::clamp(inFlight, 1, std::max(1, static_cast<int>(missing.size())));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back(worker);
    for (std::thread& t : pool)
        t.join();
    return failure;
}

} // namespace

RetrievedSeries retrieveSeries(const DicomWebSeries& series, const DicomWebAccess& access,
                               const SeriesRetrieveOptions& options) {
    DicomWebConnection connection(series.endpoint, access);
    const SeriesAnnouncement announced = announceSeries(connection, series);
    if (options.admit) options.admit(announced.grid);

    RetrievedSeries retrieved{SpoolFolder(options.spoolParent)};
    InstanceSpool spool(retrieved.folder(), announced.instanceCount, options.progress, options.cancel);
    const std::string name = series.describe();
    CancelWatch watch(options.cancel);
    {
        // A connection of its own: the admission may take longer than a PACS keeps an idle one open
        // (Orthanc: 1 s).
        DicomWebConnection pixels(series.endpoint, access);
        const WatchedConnection watched(watch, pixels);
        retrieved.seriesProblem = retrieveInto(pixels, seriesResource(series), spool);
    }
    if (spool.cancelled()) throw fit::InputError(name + ": the retrieve was cancelled");
    if (!retrieved.seriesProblem.empty() || spool.completedCount() < announced.instanceCount) {
        if (retrieved.seriesProblem.empty()) retrieved.seriesProblem = "the answer lacked instances";
        retrieved.perInstance = true;
        const std::vector<std::string> missing = missingInstances(announced, spool);
        const std::string problem =
            retrieveEach(series, access, missing, spool, options.instancesInFlight, watch);
        if (spool.cancelled()) throw fit::InputError(name + ": the retrieve was cancelled");
        if (!problem.empty())
            throw fit::InputError(name + ": the series retrieve failed (" + retrieved.seriesProblem +
                                  "), and so did the retrieve of its instances one by one (" + problem + ")");
    }
    retrieved.instanceCount = spool.completedCount();
    if (retrieved.instanceCount < announced.instanceCount)
        throw fit::InputError(name + ": received " + std::to_string(retrieved.instanceCount) +
                              " of the series' " + std::to_string(announced.instanceCount) + " instances");
    // Abbreviated metadata cannot tell images from other instances; the reader would skip the others.
    int images = 0;
    for (const fit::DicomSeriesSummary& found : fit::listDicomSeries(retrieved.folder()))
        images += found.sliceCount;
    if (images != retrieved.instanceCount)
        throw fit::InputError(name + ": " + std::to_string(retrieved.instanceCount - images) +
                              " of the series' " + std::to_string(retrieved.instanceCount) +
                              " instances are not an image; a volume needs images only");
    return retrieved;
}

} // namespace vots::pacs
