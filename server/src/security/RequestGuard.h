// The checks every request passes before a route runs: its Host, and for the API the token and the
// cross-site rules (docs/API.md, "Security").
#pragma once

#include "security/HostNames.h"
#include "vots/server/Exposure.h"

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

/// True for the requests only an operator's token may make: fits (POST /api/fit) and what goes to a PACS
/// (POST /api/pacs/{name}/store and the cancel of a store).
bool needsOperator(const std::string& method, const std::string& path);

class RequestGuard {
public:
    /// allowedHosts: the --allow-host names (throws fit::InputError for one that is not a host name);
    /// tokens: one of them is required on every API request when there are any.
    RequestGuard(const std::vector<std::string>& allowedHosts, std::vector<AccessToken> tokens);

    /// The address and port the server listens on; called before it serves.
    void bound(const std::string& host, int port);

    /// Every request, static files too: the Host must name this server (DNS rebinding), else 421.
    std::optional<Refusal> checkHost(const httplib::Request& req) const;
    /// API requests: the token (401), its role for the operator's routes (403), a foreign Origin or
    /// Sec-Fetch-Site (403), and for a request that changes state (any method but GET, HEAD, OPTIONS) a
    /// JSON Content-Type (415).
    std::optional<Refusal> checkApi(const httplib::Request& req) const;

    /// The token the request shows, when it is one of ours; null when it shows none of them.
    const AccessToken* tokenOf(const httplib::Request& req) const;
    bool requiresToken() const { return !mTokens.empty(); }
    /// False for a viewer's token: its renders draw the fits that exist, and start none at a new eps.
    bool mayStartFits(const httplib::Request& req) const;

private:
    std::vector<std::string> mAllowedHosts;
    std::vector<AccessToken> mTokens;
    HostNames mHosts;
};

} // namespace vots::server
