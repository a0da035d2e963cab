// Small helpers shared by the routes: JSON responses, the error body, and the exception-to-status table.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <exception>
#include <string>
#include <string_view>

namespace vots::server {

/// Sets status, Content-Type application/json and the body.
void sendJson(httplib::Response& res, int status, const nlohmann::json& body);
/// {"error": message} with the status.
void sendError(httplib::Response& res, int status, const std::string& message);
/// A short reason for a status httplib answers by itself ("not found", "request target too long", ...).
std::string statusText(int status);
/// What a failure tells the client: its HTTP status and the {"error"} message.
struct HttpFailure {
    int status = 500;
    std::string message;
};

/// The one table from an exception to an HTTP status, for every route, the render queue and the
/// dataset registry; the message is the exception's own (what()):
///   HttpError         its own status
///   fit::InputError   400  the request (or a file it names) cannot be accepted
///   dist::RanksOverBudget 507  a rank's z cells are over its memory budget now
///   dist::RanksLost   503  a rank stopped answering
///   std::bad_alloc    503  "out of memory" now; the client may try again
///   anything else     500
HttpFailure classifyFailure(std::exception_ptr error);
/// classifyFailure as a client is answered: a 500, which no rule expected, is logged to stderr and its
/// message reads "<unexpected>: what()".
HttpFailure httpFailureOf(std::exception_ptr error, std::string_view unexpected = "internal error");

/// 503 and 507: refused for now, not for good; the client may ask again (and a dataset that failed to load
/// so is not remembered as broken).
bool isRetryable(int status);

/// Sends httpFailureOf(error) as a JSON error. Used by httplib's exception handler.
void sendException(httplib::Response& res, std::exception_ptr error);

} // namespace vots::server
