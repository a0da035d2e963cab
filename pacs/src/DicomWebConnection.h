// One HTTP(S) connection to a DICOMweb service: authenticated GETs of JSON or of a streamed body, and POSTs.
#pragma once

#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"
#include "vots/pacs/PacsError.h"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace vots::pacs {

/// Every failure is a PacsError whose one line names the service and the problem in words (never the
/// credentials, which only the request headers carry).
class DicomWebConnection {
public:
    DicomWebConnection(const DicomWebEndpoint& endpoint, const DicomWebAccess& access);

    /// GET ROOT + `resource` answered with JSON (QIDO, metadata). A 204 or an empty body is an empty array.
    /// `what` names the request in messages ("the series' metadata").
    nlohmann::json getJson(const std::string& resource, const std::string& what);

    /// GET ROOT + `resource` with `accept`, its body handed to `receive` in chunks as it arrives.
    /// `begin` gets the answer's Content-Type once a 200 has come. Returns the HTTP status (0 when no
    /// answer came: then `failure` says why), or throws for what no retry can mend (401, 403).
    /// `begin` and `receive` return false to stop reading (they must not throw through the client).
    int getStream(const std::string& resource, const std::string& accept,
                  const std::function<bool(const std::string& contentType)>& begin,
                  const std::function<bool(const char*, std::size_t)>& receive,
                  std::optional<PacsError>& failure);

    /// POST ROOT + `resource` with a body of `length` bytes from `provide`, returning the answer.
    httplib::Result post(const std::string& resource, const std::string& contentType, std::size_t length,
                         httplib::ContentProvider provide);

    /// Ends the request in flight from another thread (its socket is shut down): a stalled answer too.
    void stop() { mClient->stop(); }

    /// "dicomweb+http://HOST:PORT/ROOT".
    std::string name() const { return mEndpoint.describe(); }

    /// The failure of an answer that is not a success: 401/403 name the credentials, 404 the resource.
    PacsError statusError(int status, const std::string& what) const;
    /// The failure of a request that got no answer; a read that failed after the read timeout's silence
    /// "timed out".
    PacsError transportError(httplib::Error error, const std::string& what) const;

private:
    using Clock = std::chrono::steady_clock;
    /// Bytes came (or a request began) now: the read timeout's silence counts from here.
    void heardFromService() { mLastHeard = Clock::now(); }

    DicomWebEndpoint mEndpoint;
    int mReadTimeoutS = 0;
    Clock::time_point mLastHeard;
    std::unique_ptr<httplib::Client> mClient;
};

} // namespace vots::pacs
