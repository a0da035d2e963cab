// The server's one exception for a request it refuses: an HTTP status (4xx/5xx) and a one-line message.
#pragma once

#include <stdexcept>
#include <string>

namespace vots::server {

/// Thrown anywhere below a route; the route wrapper turns it into {"error": what()} with status().
class HttpError : public std::runtime_error {
public:
    HttpError(int status, const std::string& message) : std::runtime_error(message), mStatus(status) {}
    int status() const { return mStatus; }

private:
    int mStatus;
};

} // namespace vots::server
