// Parsing of dicomweb+http(s):// URLs into an endpoint, or an endpoint and a series.
#include "vots/pacs/DicomWebUrl.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <cctype>

namespace vots::pacs {
namespace {

constexpr const char* HTTP_PREFIX = "dicomweb+http://";
constexpr const char* HTTPS_PREFIX = "dicomweb+https://";
constexpr std::size_t MAX_URL_LENGTH = 4096;
constexpr std::size_t MAX_UID_LENGTH = 64; // DICOM's UI value representation

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.size() >= prefix.size() &&
           std::equal(prefix.begin(), prefix.end(), text.begin(),
                      [](char p, char t) { return std::tolower(static_cast<unsigned char>(t)) == p; });
}

[[noreturn]] void refuse(const std::string& problem) {
    throw fit::InputError("DICOMweb URL: " + problem);
}

bool isUid(const std::string& uid) {
    return !uid.empty() && uid.size() <= MAX_UID_LENGTH &&
           std::all_of(uid.begin(), uid.end(), [](char c) { return c == '.' || (c >= '0' && c <= '9'); });
}

int parsePort(const std::string& text) {
    if (text.empty() || text.size() > 5 ||
        !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        refuse("the port '" + text + "' is not a number 1..65535");
    const int port = std::stoi(text);
    if (port < 1 || port > 65535) refuse("the port '" + text + "' is not a number 1..65535");
    return port;
}

bool isHostCharacter(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
}

/// The endpoint, and the path after the authority (starting with '/', or empty).
DicomWebEndpoint parseAuthority(const std::string& url, std::string& path) {
    if (url.size() > MAX_URL_LENGTH) refuse("longer than " + std::to_string(MAX_URL_LENGTH) + " characters");
    DicomWebEndpoint e;
    std::size_t start = 0;
    if (startsWith(url, HTTPS_PREFIX)) {
        e.https = true;
        start = std::string(HTTPS_PREFIX).size();
    } else if (startsWith(url, HTTP_PREFIX)) {
        start = std::string(HTTP_PREFIX).size();
    } else {
        refuse("it must start with dicomweb+http:// or dicomweb+https://");
    }
    const std::size_t slash = url.find('/', start);
    const std::string authority =
        url.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    path = slash == std::string::npos ? std::string() : url.substr(slash);
    // Not echoed: whatever precedes '@' may be a password.
    if (authority.find('@') != std::string::npos)
        refuse("credentials in the URL are not accepted; put them in a --dicomweb-auth file");
    if (path.find_first_of("?#") != std::string::npos)
        refuse("a query or fragment is not part of a series URL");
    std::string portText;
    if (!authority.empty() && authority.front() == '[') {
        const std::size_t close = authority.find(']');
        if (close == std::string::npos) refuse("unclosed '[' in the host");
        e.host = authority.substr(1, close - 1);
        if (close + 1 < authority.size()) {
            if (authority[close + 1] != ':') refuse("unexpected text after the host's ']'");
            portText = authority.substr(close + 2);
            if (portText.empty()) refuse("an empty port after ':'");
        }
    } else {
        const std::size_t colon = authority.find(':');
        e.host = authority.substr(0, colon);
        if (colon != std::string::npos) {
            portText = authority.substr(colon + 1);
            if (portText.empty()) refuse("an empty port after ':'");
        }
        if (!std::all_of(e.host.begin(), e.host.end(), isHostCharacter))
            refuse("the host '" + e.host + "' has characters a host name cannot have");
    }
    if (e.host.empty()) refuse("no host");
    e.port = portText.empty() ? (e.https ? 443 : 80) : parsePort(portText);
    return e;
}

std::string withoutTrailingSlashes(std::string path) {
    while (!path.empty() && path.back() == '/')
        path.pop_back();
    return path;
}

} // namespace

std::string DicomWebEndpoint::describe() const {
    const bool bracket = host.find(':') != std::string::npos;
    return std::string(https ? HTTPS_PREFIX : HTTP_PREFIX) + (bracket ? "[" + host + "]" : host) + ":" +
           std::to_string(port) + root;
}

std::string DicomWebSeries::describe() const {
    return endpoint.describe() + "/studies/" + studyUid + "/series/" + seriesUid;
}

bool isDicomWebUrl(const std::string& text) {
    return startsWith(text, HTTP_PREFIX) || startsWith(text, HTTPS_PREFIX);
}

DicomWebEndpoint parseDicomWebEndpoint(const std::string& url) {
    std::string path;
    DicomWebEndpoint e = parseAuthority(url, path);
    e.root = withoutTrailingSlashes(path);
    return e;
}

DicomWebSeries parseDicomWebSeriesUrl(const std::string& url) {
    std::string path;
    DicomWebSeries s;
    s.endpoint = parseAuthority(url, path);
    path = withoutTrailingSlashes(path);
    const std::size_t studies = path.rfind("/studies/");
    const std::size_t series = path.rfind("/series/");
    if (studies == std::string::npos || series == std::string::npos || series < studies)
        refuse("a series URL ends in /studies/STUDY_UID/series/SERIES_UID");
    s.endpoint.root = path.substr(0, studies);
    const std::size_t studyStart = studies + std::string("/studies/").size();
    s.studyUid = path.substr(studyStart, series - studyStart);
    s.seriesUid = path.substr(series + std::string("/series/").size());
    if (!isUid(s.studyUid)) refuse("the study UID '" + s.studyUid + "' is not a DICOM UID (digits and dots)");
    if (!isUid(s.seriesUid))
        refuse("the series UID '" + s.seriesUid + "' is not a DICOM UID (digits and dots)");
    return s;
}

} // namespace vots::pacs
