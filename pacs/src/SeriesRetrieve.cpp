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
#include <optional>
#include <set>
#include <thread>

namespace vots::pacs {
namespace {

/// One multipart GET into the spool; nullopt when every part of a complete answer is in, else why not.
std::optional<PacsError> retrieveInto(DicomWebConnection& connection, const std::string& resource,
                                      InstanceSpool& spool) {
    SpoolStream stream(spool);
    std::optional<PacsError> failure;
    const int status = connection.getStream(
        resource, DICOM_MULTIPART_ACCEPT, [&](const std::string& type) { return stream.begin(type); },
        [&](const char* data, std::size_t size) { return stream.receive(data, size); }, failure);
    if (!stream.problem().empty()) return stream.error();
    if (status != 200) return failure ? *failure : connection.statusError(status, "the request");
    if (failure) {
        stream.finish(); // removes a half-written part
        return failure;
    }
    if (!stream.finish()) return stream.error();
    return std::nullopt;
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

/// Fetches `missing` one request each, `inFlight` at a time; nullopt, or the first failure.
std::optional<PacsError> retrieveEach(const DicomWebSeries& series, const DicomWebAccess& access,
                                      const std::vector<std::string>& missing, InstanceSpool& spool,
                                      int inFlight, CancelWatch& watch) {
    std::atomic<std::size_t> next{0};
    std::mutex failureMutex;
    std::optional<PacsError> failure;
    const auto failed = [&] {
        std::lock_guard lock(failureMutex);
        return failure.has_value();
    };
    const auto worker = [&] {
        try {
            DicomWebConnection connection(series.endpoint, access);
            const WatchedConnection watched(watch, connection);
            for (std::size_t i = next++; i < missing.size() && !failed(); i = next++) {
                const std::optional<PacsError> problem =
                    retrieveInto(connection, seriesResource(series) + "/instances/" + missing[i], spool);
                if (problem) {
                    std::lock_guard lock(failureMutex);
                    if (!failure)
                        failure =
                            PacsError(problem->kind(), "instance " + missing[i] + ": " + problem->what());
                }
            }
        } catch (const PacsError& e) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = e;
        } catch (const std::exception& e) {
            std::lock_guard lock(failureMutex);
            if (!failure) failure = PacsError(PacsFailure::Cut, e.what());
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
    const SeriesAnnouncement announced =
        options.announced ? *options.announced : announceSeries(series, access);
    if (options.admit) options.admit(announced.grid);

    RetrievedSeries retrieved{SpoolFolder(options.spoolParent)};
    InstanceSpool spool(retrieved.folder(), announced.instanceCount, options.progress, options.received,
                        options.cancel);
    const std::string name = series.describe();
    CancelWatch watch(options.cancel);
    {
        // A connection of its own: the admission may take longer than a PACS keeps an idle one open
        // (Orthanc: 1 s).
        DicomWebConnection pixels(series.endpoint, access);
        const WatchedConnection watched(watch, pixels);
        if (const std::optional<PacsError> problem = retrieveInto(pixels, seriesResource(series), spool))
            retrieved.seriesProblem = problem->what();
    }
    const PacsError cancelled(PacsFailure::Cancelled, name + ": the retrieve was cancelled");
    if (spool.cancelled()) throw cancelled;
    if (!retrieved.seriesProblem.empty() || spool.completedCount() < announced.instanceCount) {
        if (retrieved.seriesProblem.empty()) retrieved.seriesProblem = "the answer lacked instances";
        retrieved.perInstance = true;
        const std::vector<std::string> missing = missingInstances(announced, spool);
        const std::optional<PacsError> problem =
            retrieveEach(series, access, missing, spool, options.instancesInFlight, watch);
        if (spool.cancelled()) throw cancelled;
        if (problem)
            throw PacsError(problem->kind(), name + ": the series retrieve failed (" +
                                                 retrieved.seriesProblem +
                                                 "), and so did the retrieve of its instances one by one (" +
                                                 problem->what() + ")");
    }
    retrieved.instanceCount = spool.completedCount();
    if (retrieved.instanceCount < announced.instanceCount)
        throw PacsError(PacsFailure::Cut, name + ": received " + std::to_string(retrieved.instanceCount) +
                                              " of the series' " + std::to_string(announced.instanceCount) +
                                              " instances");
    // Abbreviated metadata cannot tell images from other instances; the reader would skip the others.
    int images = 0;
    if (options.countImages)
        images = options.countImages();
    else
        for (const fit::DicomSeriesSummary& found : fit::listDicomSeries(retrieved.folder()))
            images += found.sliceCount;
    if (images != retrieved.instanceCount)
        throw PacsError(PacsFailure::NotImages,
                        name + ": " + std::to_string(retrieved.instanceCount - images) + " of the series' " +
                            std::to_string(retrieved.instanceCount) +
                            " instances are not an image; a volume needs images only");
    return retrieved;
}

} // namespace vots::pacs
