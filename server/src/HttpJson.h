// Small helpers shared by the routes: JSON responses, the error body, and exception-to-status mapping.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <exception>
#include <string>

namespace vots::server {

/// Sets status, Content-Type application/json and the body.
void sendJson(httplib::Response& res, int status, const nlohmann::json& body);
/// {"error": message} with the status.
void sendError(httplib::Response& res, int status, const std::string& message);
/// A short reason for a status httplib answers by itself ("not found", "request target too long", ...).
std::string statusText(int status);
/// Maps an escaped exception to a JSON error: HttpError keeps its status, fit::InputError is 400,
/// bad_alloc 503, anything else 500. Used by httplib's exception handler.
void sendException(httplib::Response& res, std::exception_ptr error);

} // namespace vots::server
