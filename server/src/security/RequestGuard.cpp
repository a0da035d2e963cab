// Host, token and cross-site checks ahead of the routes (see RequestGuard.h and docs/API.md, "Security").
#include "security/RequestGuard.h"

#include "routes/Params.h"

#include <algorithm>
#include <cctype>
#include <regex>

namespace vots::server {
namespace {

constexpr std::size_t MAX_QUOTED_CHARS = 100; // of a refused Host or Origin in the error message

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t'))
        text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t'))
        text.remove_suffix(1);
    return text;
}

/// The token the request shows: the Authorization header's Bearer credential, else the token= query
/// parameter (for EventSource, which cannot set headers); empty when it shows none.
std::string presentedToken(const httplib::Request& req) {
    if (req.has_header("Authorization")) {
        const std::string value = req.get_header_value("Authorization");
        if (value.size() > 7 && lower(value.substr(0, 7)) == "bearer ")
            return std::string(trimmed(std::string_view(value).substr(7)));
        return {}; // another scheme: no token
    }
    const QueryParams query = targetQueryParams(req.target);
    const auto it = query.find("token");
    return it == query.end() ? std::string() : it->second;
}

bool changesState(const std::string& method) {
    return method != "GET" && method != "HEAD" && method != "OPTIONS";
}

/// "application/json; charset=utf-8" -> "application/json".
std::string mediaType(const std::string& contentType) {
    return lower(trimmed(std::string_view(contentType).substr(0, contentType.find(';'))));
}

} // namespace

bool tokensEqual(std::string_view presented, std::string_view expected) {
    unsigned difference = presented.size() == expected.size() ? 0u : 1u;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const char shown = i < presented.size() ? presented[i] : '\0';
        difference |= static_cast<unsigned char>(shown ^ expected[i]); // no early exit on a mismatch
    }
    return difference == 0;
}

bool needsOperator(const std::string& method, const std::string& path) {
    static const std::regex operatorPaths(R"(/api/fit|/api/pacs/[^/]+/store|/api/pacs/stores/\d+/cancel)");
    return method == "POST" && std::regex_match(path, operatorPaths);
}

RequestGuard::RequestGuard(const std::vector<std::string>& allowedHosts, std::vector<AccessToken> tokens)
    : mAllowedHosts(allowedHosts), mTokens(std::move(tokens)), mHosts("127.0.0.1", 0, allowedHosts) {}

const AccessToken* RequestGuard::tokenOf(const httplib::Request& req) const {
    const std::string presented = presentedToken(req);
    const AccessToken* match = nullptr;
    for (const AccessToken& t : mTokens) // every one compared: the time does not tell which matched
        if (tokensEqual(presented, t.token)) match = &t;
    return match;
}

bool RequestGuard::mayStartFits(const httplib::Request& req) const {
    if (mTokens.empty()) return true;
    const AccessToken* token = tokenOf(req);
    return token && token->role == Role::Operator;
}

void RequestGuard::bound(const std::string& host, int port) {
    mHosts = HostNames(host, port, mAllowedHosts);
}

std::optional<Refusal> RequestGuard::checkHost(const httplib::Request& req) const {
    // No Host at all comes from HTTP/1.0 tools only: a browser always sends one, so it is no rebinding.
    if (!req.has_header("Host")) return std::nullopt;
    if (req.get_header_value_count("Host") > 1) return Refusal{400, "more than one Host header"};
    const std::string host = req.get_header_value("Host");
    if (mHosts.answers(host)) return std::nullopt;
    return Refusal{421, "this server does not answer to the name '" + host.substr(0, MAX_QUOTED_CHARS) +
                            "' (vots serve --allow-host adds names)"};
}

std::optional<Refusal> RequestGuard::checkApi(const httplib::Request& req) const {
    if (!mTokens.empty()) {
        const AccessToken* token = tokenOf(req);
        if (!token)
            return Refusal{401, "missing or wrong access token (send 'Authorization: Bearer TOKEN', or "
                                "token=TOKEN in the query; the viewer takes it from #token=TOKEN)"};
        if (token->role == Role::Viewer && needsOperator(req.method, req.path))
            return Refusal{403, "the token of '" + token->name + "' is a viewer's: " + req.method + " " +
                                    req.path.substr(0, MAX_QUOTED_CHARS) + " needs an operator's token"};
    }
    // Browsers name the site a request comes from; a page of another one must not start fits, nor
    // have its <img> tags make us render.
    const std::string site = req.get_header_value("Sec-Fetch-Site");
    if (!site.empty() && site != "same-origin" && site != "none")
        return Refusal{403, "requests from other sites are refused (Sec-Fetch-Site: " +
                                site.substr(0, MAX_QUOTED_CHARS) + ")"};
    if (req.has_header("Origin") &&
        !isSameOrigin(req.get_header_value("Origin"), req.get_header_value("Host")))
        return Refusal{403, "requests from other origins are refused (Origin: " +
                                req.get_header_value("Origin").substr(0, MAX_QUOTED_CHARS) + ")"};
    // A page may POST text/plain or a form to any site without asking first; JSON it may not.
    if (changesState(req.method) && mediaType(req.get_header_value("Content-Type")) != "application/json")
        return Refusal{415, req.method + " requests need 'Content-Type: application/json'"};
    return std::nullopt;
}

} // namespace vots::server
