// The authenticated HTTP(S) client of a DICOMweb service, and the words for its failures.
#include "DicomWebConnection.h"

#include <algorithm>

namespace vots::pacs {
namespace {

constexpr time_t CONNECT_TIMEOUT_S = 10;
constexpr std::size_t MAX_JSON_BYTES = 256u << 20; // a 1000-instance series' full metadata is ~30 MB

} // namespace

DicomWebConnection::DicomWebConnection(const DicomWebEndpoint& endpoint, const DicomWebAccess& access)
    : mEndpoint(endpoint), mReadTimeoutS(std::max(1, access.readTimeoutSeconds)) {
    const bool bracket = endpoint.host.find(':') != std::string::npos;
    const std::string origin = std::string(endpoint.https ? "https://" : "http://") +
                               (bracket ? "[" + endpoint.host + "]" : endpoint.host) + ":" +
                               std::to_string(endpoint.port);
    mClient = std::make_unique<httplib::Client>(origin);
    if (!mClient->is_valid())
        throw PacsError(PacsFailure::Unreachable, name() + ": cannot make a client for this address");
    mClient->set_connection_timeout(CONNECT_TIMEOUT_S);
    mClient->set_read_timeout(mReadTimeoutS);
    mClient->set_keep_alive(true);
    if (endpoint.https) {
        mClient->enable_server_certificate_verification(true);
        if (!access.caFile.empty()) mClient->set_ca_cert_path(access.caFile);
    }
    if (access.auth.kind == DicomWebAuth::Kind::Basic)
        mClient->set_basic_auth(access.auth.user, access.auth.secret);
    if (access.auth.kind == DicomWebAuth::Kind::Bearer) mClient->set_bearer_token_auth(access.auth.secret);
}

PacsError DicomWebConnection::statusError(int status, const std::string& what) const {
    const std::string code = " (HTTP " + std::to_string(status) + ")";
    if (status == 401)
        return {PacsFailure::Unauthorized,
                name() + ": the PACS refused the credentials for " + what + code + "; check --dicomweb-auth"};
    if (status == 403)
        return {PacsFailure::Unauthorized,
                name() + ": the PACS forbids " + what + " to these credentials" + code};
    if (status == 404) return {PacsFailure::NotFound, name() + ": " + what + " not found" + code};
    return {PacsFailure::Refused, name() + ": the PACS answered " + what + " with an error" + code};
}

PacsError DicomWebConnection::transportError(httplib::Error error, const std::string& what) const {
    switch (error) {
    case httplib::Error::Connection:
        return {PacsFailure::Unreachable, name() + ": cannot connect to " + mEndpoint.host + ":" +
                                              std::to_string(mEndpoint.port) + " for " + what +
                                              " (nothing answers there)"};
    case httplib::Error::SSLConnection:
    case httplib::Error::SSLLoadingCerts:
    case httplib::Error::SSLServerVerification:
        return {PacsFailure::Unreachable, name() + ": the TLS connection for " + what + " failed (" +
                                              httplib::to_string(error) +
                                              "); check the certificate or --dicomweb-ca"};
    case httplib::Error::Read:
        if (Clock::now() - mLastHeard >= std::chrono::seconds(mReadTimeoutS))
            return {PacsFailure::TimedOut, name() + ": " + what + " timed out (no answer for " +
                                               std::to_string(mReadTimeoutS) + " s)"};
        return {PacsFailure::Cut, name() + ": the connection broke while reading " + what};
    case httplib::Error::Canceled:
        return {PacsFailure::Cancelled, name() + ": " + what + " was cancelled"};
    default:
        return {PacsFailure::Cut, name() + ": " + what + " failed (" + httplib::to_string(error) + ")"};
    }
}

nlohmann::json DicomWebConnection::getJson(const std::string& resource, const std::string& what) {
    std::string body;
    int status = 0;
    bool tooLarge = false;
    const httplib::Headers headers{{"Accept", "application/dicom+json, application/json"}};
    heardFromService();
    const httplib::Result result = mClient->Get(
        mEndpoint.root + resource, headers,
        [&](const httplib::Response& response) {
            status = response.status;
            return true;
        },
        [&](const char* data, std::size_t size) {
            heardFromService();
            tooLarge = body.size() + size > MAX_JSON_BYTES;
            if (tooLarge) return false;
            body.append(data, size);
            return true;
        });
    if (tooLarge)
        throw PacsError(PacsFailure::TooBig, name() + ": " + what + " is larger than " +
                                                 std::to_string(MAX_JSON_BYTES >> 20) + " MB");
    if (!result) throw transportError(result.error(), what);
    if (status == 204 || (status == 200 && body.empty())) return nlohmann::json::array();
    if (status != 200) throw statusError(status, what);
    nlohmann::json json = nlohmann::json::parse(body, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded()) throw PacsError(PacsFailure::Malformed, name() + ": " + what + " is not JSON");
    return json;
}

int DicomWebConnection::getStream(const std::string& resource, const std::string& accept,
                                  const std::function<bool(const std::string&)>& begin,
                                  const std::function<bool(const char*, std::size_t)>& receive,
                                  std::optional<PacsError>& failure) {
    int status = 0;
    const httplib::Headers headers{{"Accept", accept}};
    heardFromService();
    const httplib::Result result = mClient->Get(
        mEndpoint.root + resource, headers,
        [&](const httplib::Response& response) {
            status = response.status;
            if (status != 200) return false;
            return begin(response.get_header_value("Content-Type"));
        },
        [&](const char* data, std::size_t size) {
            heardFromService();
            return receive(data, size);
        });
    if (status == 401 || status == 403) throw statusError(status, "the series");
    if (status != 0 && status != 200) return status;
    if (!result && result.error() != httplib::Error::Canceled) {
        failure = transportError(result.error(), "the series");
        return status;
    }
    return status;
}

httplib::Result DicomWebConnection::post(const std::string& resource, const std::string& contentType,
                                         std::size_t length, httplib::ContentProvider provide) {
    heardFromService();
    return mClient->Post(mEndpoint.root + resource, httplib::Headers{{"Accept", "application/dicom+json"}},
                         length, std::move(provide), contentType);
}

} // namespace vots::pacs
