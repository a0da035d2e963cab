// The pacs module's failures: one line for the user (a fit::InputError, so the CLI exits 2) and a kind
// that callers map (the server to an HTTP status) without reading the words.
#pragma once

#include "vots/fit/Error.h"

#include <string>

namespace vots::pacs {

enum class PacsFailure {
    Unreachable,  // nothing answers at the address, or TLS cannot be set up
    Unauthorized, // the PACS refused the credentials (its 401 or 403)
    NotFound,     // no such study, series or instance (its 404, or an empty search)
    TimedOut,     // the PACS went silent for longer than the read timeout
    Refused,      // the PACS answered with another error status, or refused stored instances
    Cut,          // the connection broke, or an answer ended early
    Malformed,    // an answer that is not what DICOMweb says (not JSON, not multipart, a bad part)
    NotImages,    // the series holds instances that are not images, or images of mixed sizes
    TooBig,       // an answer larger than the client accepts
    Cancelled,    // stopped by the caller
    BadRequest,   // the caller's own request is malformed (a date, a UID)
    Local,        // this machine failed: a spool file that cannot be written
};

class PacsError : public fit::InputError {
public:
    PacsError(PacsFailure kind, const std::string& message) : fit::InputError(message), mKind(kind) {}
    PacsFailure kind() const { return mKind; }

private:
    PacsFailure mKind;
};

} // namespace vots::pacs
