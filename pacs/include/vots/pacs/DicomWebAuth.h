// How Vots authenticates to a DICOMweb service: the --dicomweb-auth file and the https trust anchors.
#pragma once

#include <string>

namespace vots::pacs {

/// The credentials of one service. Never printed: messages name the auth file, not its contents.
struct DicomWebAuth {
    enum class Kind { None, Basic, Bearer };
    Kind kind = Kind::None;
    std::string user;   // Basic only
    std::string secret; // the Basic password or the bearer token
};

/// Everything a connection needs besides the endpoint.
struct DicomWebAccess {
    DicomWebAuth auth;
    std::string caFile; // PEM certificates to verify an https service with; empty: the system's store
    /// Longest wait for the next bytes of an answer; a longer silence fails as "timed out".
    int readTimeoutSeconds = 120;
};

/// Reads an auth file whose one line is "basic USER:PASSWORD" or "bearer TOKEN" (a trailing newline is
/// fine). Throws fit::InputError with one line naming the file and the problem, never its contents.
DicomWebAuth readDicomWebAuthFile(const std::string& path);

} // namespace vots::pacs
