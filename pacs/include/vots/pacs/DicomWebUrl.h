// The dicomweb+http(s):// URLs that name a DICOMweb service (for storing) or one series on it (an input).
#pragma once

#include <string>

namespace vots::pacs {

/// A DICOMweb service: scheme, host, port and the root path its QIDO/WADO/STOW resources hang from.
struct DicomWebEndpoint {
    bool https = false;
    std::string host;
    int port = 0;
    std::string root; // "/dicom-web" (no trailing slash), or empty for a service at the server's root

    /// "dicomweb+http://HOST:PORT/ROOT": names the service in messages and meta blocks (it never holds
    /// credentials: URLs with user information are refused).
    std::string describe() const;
};

/// One series on a DICOMweb service.
struct DicomWebSeries {
    DicomWebEndpoint endpoint;
    std::string studyUid;
    std::string seriesUid;

    /// "dicomweb+http://HOST:PORT/ROOT/studies/STUDY/series/SERIES".
    std::string describe() const;
};

/// True for text that starts with dicomweb+http:// or dicomweb+https://: such an input is a PACS series.
bool isDicomWebUrl(const std::string& text);

/// Parses "dicomweb+http(s)://HOST[:PORT][/ROOT]" (port default 80 or 443). Throws fit::InputError with
/// one line for anything else, and for user information in the URL (credentials go in an auth file).
DicomWebEndpoint parseDicomWebEndpoint(const std::string& url);

/// Parses "dicomweb+http(s)://HOST[:PORT][/ROOT]/studies/STUDY_UID/series/SERIES_UID"; throws
/// fit::InputError as parseDicomWebEndpoint does, and when the UIDs are missing or malformed.
DicomWebSeries parseDicomWebSeriesUrl(const std::string& url);

} // namespace vots::pacs
