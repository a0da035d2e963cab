// The access a PACS search runs with: a search is answered on an HTTP worker, which must not wait long.
#pragma once

#include "vots/server/Server.h"

#include <algorithm>

namespace vots::server {

/// Longest silence of a PACS during a QIDO search before it fails as timed out (504): a search answers
/// in well under a second on a healthy PACS, and the worker it holds serves nothing else meanwhile.
inline constexpr int SEARCH_TIMEOUT_S = 15;

/// `service`'s access with the search's read timeout.
inline pacs::DicomWebAccess searchAccess(const DicomWebService& service) {
    pacs::DicomWebAccess access = service.access;
    access.readTimeoutSeconds = std::min(access.readTimeoutSeconds, SEARCH_TIMEOUT_S);
    return access;
}

} // namespace vots::server
