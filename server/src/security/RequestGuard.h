// The checks every request passes before a route runs: its Host, and for the API the token and the
// cross-site rules (docs/API.md, "Security").
#pragma once

#include "security/HostNames.h"

#include <httplib.h>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vots::server {

/// Why a request is refused: the status and the one-line message of its JSON error.
struct Refusal {
    int status = 0;
    std::string message;
};

/// Compares a presented token with the expected one in time that depends on the expected length only,
/// so timing the 401s tells nothing about how much of a guess was right.
bool tokensEqual(std::string_view presented, std::string_view expected);

class RequestGuard {
public:
    /// allowedHosts: the --allow-host names (throws fit::InputError for one that is not a host name);
    /// token: required on every API request when not empty.
    RequestGuard(const std::vector<std::string>& allowedHosts, std::string token);

    /// The address and port the server listens on; called before it serves.
    void bound(const std::string& host, int port);

    /// Every request, static files too: the Host must name this server (DNS rebinding), else 421.
    std::optional<Refusal> checkHost(const httplib::Request& req) const;
    /// API requests: the token (401), a foreign Origin or Sec-Fetch-Site (403), and for a request that
    /// changes state (any method but GET, HEAD, OPTIONS) a JSON Content-Type (415).
    std::optional<Refusal> checkApi(const httplib::Request& req) const;

    bool requiresToken() const { return !mToken.empty(); }

private:
    std::vector<std::string> mAllowedHosts;
    std::string mToken;
    HostNames mHosts;
};

} // namespace vots::server
