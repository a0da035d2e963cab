// Storing DICOM files on a DICOMweb service (STOW-RS) in one multipart/related request.
#pragma once

#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"

#include <atomic>
#include <string>
#include <vector>

namespace vots::pacs {

struct StoreReport {
    int stored = 0; // instances the service says it stored (ReferencedSOPSequence)
};

/// POSTs `files` to ROOT/studies as one multipart/related; type="application/dicom" body, streamed from
/// the files. Throws fit::InputError with one line when the request fails or the service refuses any
/// instance (FailedSOPSequence: the first failed SOPInstanceUID and its FailureReason, and how many failed).
/// `cancel`, set from any thread, ends the request in flight (PacsFailure::Cancelled): the body is cut
/// before its end, so a DICOMweb service, which stores a request's instances once it has them all,
/// stores none.
StoreReport storeInstances(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                           const std::vector<std::string>& files, const std::atomic<bool>* cancel = nullptr);

} // namespace vots::pacs
