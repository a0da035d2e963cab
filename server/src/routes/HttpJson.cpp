// JSON response helpers and the one place that decides which exception becomes which HTTP status.
#include "routes/HttpJson.h"

#include "HttpError.h"
#include "vots/dist/Failure.h"
#include "vots/fit/Error.h"

#include <iostream>
#include <new>

namespace vots::server {

void sendJson(httplib::Response& res, int status, const nlohmann::json& body) {
    res.status = status;
    // replace: invalid UTF-8 in a message (from a file name, say) must not throw while answering
    res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "application/json");
}

void sendError(httplib::Response& res, int status, const std::string& message) {
    sendJson(res, status, nlohmann::json{{"error", message}});
}

std::string statusText(int status) {
    switch (status) {
    case 400:
        return "bad request";
    case 404:
        return "not found";
    case 405:
        return "method not allowed";
    case 413:
        return "request body too large";
    case 414:
        return "request target too long";
    case 415:
        return "unsupported media type";
    case 416:
        return "range not satisfiable";
    case 503:
        return "service unavailable";
    default:
        return "HTTP status " + std::to_string(status);
    }
}

HttpFailure classifyFailure(std::exception_ptr error) {
    try {
        std::rethrow_exception(error);
    } catch (const HttpError& e) {
        return {e.status(), e.what()};
    } catch (const fit::InputError& e) {
        return {400, e.what()};
    } catch (const dist::RanksOverBudget& e) {
        return {507, e.what()};
    } catch (const dist::RanksLost& e) { // logged once by the ranks' port
        return {503, e.what()};
    } catch (const std::bad_alloc&) {
        return {503, "out of memory"};
    } catch (const std::exception& e) {
        return {500, e.what()};
    } catch (...) {
        return {500, "unknown exception"};
    }
}

HttpFailure httpFailureOf(std::exception_ptr error, std::string_view unexpected) {
    HttpFailure failure = classifyFailure(error);
    if (failure.status == 500) {
        std::cerr << "vots serve: " << unexpected << ": " << failure.message << "\n";
        failure.message = std::string(unexpected) + ": " + failure.message;
    }
    return failure;
}

bool isRetryable(int status) {
    return status == 503 || status == 507;
}

void sendException(httplib::Response& res, std::exception_ptr error) {
    const HttpFailure failure = httpFailureOf(error);
    sendError(res, failure.status, failure.message);
}

} // namespace vots::server
