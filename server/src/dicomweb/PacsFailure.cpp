// The pacs module's failures as HTTP statuses, read from the words of its one-line messages
// (pacs/src/DicomWebConnection.cpp: statusProblem and transportProblem).
#include "dicomweb/PacsFailure.h"

#include <string>

namespace vots::server {
namespace {

bool has(const std::string& text, const char* part) {
    return text.find(part) != std::string::npos;
}

int statusOf(const std::string& message) {
    if (has(message, "(HTTP 401)") || has(message, "(HTTP 403)")) return 401;
    if (has(message, "(HTTP 404)") || has(message, "no such series on the PACS")) return 404;
    if (has(message, "Timeout") || has(message, "timed out")) return 504;
    return 502;
}

} // namespace

HttpError pacsFailure(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const HttpError& e) {
        return e;
    } catch (const std::exception& e) {
        return HttpError(statusOf(e.what()), e.what());
    } catch (...) {
        return HttpError(502, "the PACS request failed");
    }
}

} // namespace vots::server
