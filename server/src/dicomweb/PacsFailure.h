// What a failed PACS request tells the viewer: the HTTP status for the pacs module's failures.
#pragma once

#include "HttpError.h"

#include <exception>

namespace vots::server {

/// The status for a pacs::searchStudies / searchSeries / announceSeries / retrieveSeries / storeInstances
/// failure, from its kind (pacs::PacsFailure), with its message (which names the service, never the
/// credentials):
///   401  the PACS refused the credentials (its 401 or 403)
///   404  the study or series is not on the PACS
///   504  the PACS did not answer in time
///   409  the request was cancelled
///   400  the request itself is malformed (a date, a UID)
///   500  this server failed (a spool file it cannot write)
///   502  anything else: nothing answers, the connection broke, an error status, a malformed answer
/// An HttpError (the memory budget's 507) keeps its own status.
HttpError pacsFailure(std::exception_ptr error);

} // namespace vots::server
