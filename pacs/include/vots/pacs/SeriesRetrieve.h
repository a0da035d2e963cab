// Retrieving one series from a DICOMweb service (WADO-RS) into a spool folder the DICOM reader reads.
#pragma once

#include "vots/fit/VolumeHeader.h"
#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"
#include "vots/pacs/SpoolFolder.h"

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vots::pacs {

/// What QIDO-RS and the series' metadata say before any pixels come.
struct SeriesAnnouncement {
    int instanceCount = 0;
    fit::VolumeHeaderInfo grid; // columns x rows x instances and the type the samples will load into
    std::vector<std::string> sopInstanceUids;
};

/// Asks the service about the series (QIDO-RS, then WADO-RS metadata). Throws fit::InputError with one
/// line for an unknown series, an instance that is not an image, mixed image sizes, refused credentials
/// or a service that cannot be reached.
SeriesAnnouncement announceSeries(const DicomWebSeries& series, const DicomWebAccess& access);

struct SeriesRetrieveOptions {
    std::string spoolParent; // where the spool folder is made; empty: $TMPDIR or /tmp
    /// The series' announcement when the caller has just asked for it (announceSeries): the retrieve
    /// then starts on the pixels at once instead of asking again (QIDO and metadata: a second or more
    /// for a thousand instances). Empty: the retrieve announces the series itself.
    std::optional<SeriesAnnouncement> announced;
    /// Called with the announced grid before the pixels are asked for; throws to refuse (memory budget).
    std::function<void(const fit::VolumeHeaderInfo&)> admit;
    /// Instances received so far and the series' count; called from the retrieving threads, in order.
    std::function<void(int received, int total)> progress;
    /// Each instance's file as soon as it is complete in the spool folder (from the retrieving threads, one
    /// at a time), so that a reader may start on it while the rest arrive.
    std::function<void(const std::string& path)> received;
    /// How many of the instances received are images, asked once all are in; empty: the spool folder's
    /// headers are read for it. A series needs images only.
    std::function<int()> countImages;
    /// Set from any thread to stop the retrieve, which then throws fit::InputError.
    const std::atomic<bool>* cancel = nullptr;
    int instancesInFlight = 4; // per-instance requests at once when the series request fails
};

/// A retrieved series: a folder of its instances, one file each; the folder goes with the object.
class RetrievedSeries {
public:
    explicit RetrievedSeries(SpoolFolder folder) : mFolder(std::move(folder)) {}
    const std::string& folder() const { return mFolder.path(); }
    /// Keeps the instances as the folder `destination` instead of removing them (SpoolFolder::keepAs).
    void keepAs(const std::string& destination) { mFolder.keepAs(destination); }

    int instanceCount = 0;
    bool perInstance = false;  // the series request failed and the instances came one by one
    std::string seriesProblem; // why the series request failed (empty when it did not)

private:
    SpoolFolder mFolder;
};

/// One series-level request (multipart/related; type="application/dicom"; transfer-syntax=*), split as
/// it streams, each instance written to the spool folder as it arrives; when that request is refused or
/// cut, the instances not yet received are asked for one by one, a few at a time. Throws fit::InputError
/// with one line (naming the series URL, never the credentials) and leaves no folder behind on failure.
RetrievedSeries retrieveSeries(const DicomWebSeries& series, const DicomWebAccess& access,
                               const SeriesRetrieveOptions& options = {});

} // namespace vots::pacs
