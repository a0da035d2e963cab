// Host header and Origin parsing, and the lists of names a server answers to (see HostNames.h).
#include "security/HostNames.h"

#include "vots/fit/Error.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>

namespace vots::server {
namespace {

constexpr std::size_t MAX_AUTHORITY_CHARS = 300; // a DNS name is at most 253, plus a port

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

bool isNameChar(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
}

bool isIpv4(const std::string& text) {
    in_addr addr{};
    return inet_pton(AF_INET, text.c_str(), &addr) == 1;
}

/// The canonical text of an IPv6 address ("0:0::1" -> "::1"), or nullopt.
std::optional<std::string> canonicalIpv6(const std::string& text) {
    in6_addr addr{};
    if (inet_pton(AF_INET6, text.c_str(), &addr) != 1) return std::nullopt;
    char out[INET6_ADDRSTRLEN] = {};
    if (!inet_ntop(AF_INET6, &addr, out, sizeof out)) return std::nullopt;
    return std::string(out);
}

/// Reads ":digits" after the name, or nothing, into `port`; false for anything else or a port outside
/// 1..65535.
bool parsePort(std::string_view rest, std::optional<int>& port) {
    port.reset();
    if (rest.empty()) return true;
    if (rest[0] != ':' || rest.size() < 2 || rest.size() > 6) return false;
    int value = 0;
    for (const char c : rest.substr(1)) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + (c - '0');
    }
    if (value < 1 || value > 65535) return false;
    port = value;
    return true;
}

/// A bound --host as the name a Host header would carry: IPv6 addresses bracketed and canonical.
std::string hostHeaderName(const std::string& host) {
    const std::string bare =
        host.size() > 1 && host.front() == '[' && host.back() == ']' ? host.substr(1, host.size() - 2) : host;
    if (const auto v6 = canonicalIpv6(bare)) return "[" + *v6 + "]";
    return lower(host);
}

bool sameAuthority(const Authority& a, const Authority& b) {
    return a.name == b.name && a.port == b.port;
}

} // namespace

std::optional<Authority> parseAuthority(std::string_view text) {
    if (text.empty() || text.size() > MAX_AUTHORITY_CHARS) return std::nullopt;
    Authority out;
    std::string_view rest;
    if (text[0] == '[') {
        const auto close = text.find(']');
        if (close == std::string_view::npos) return std::nullopt;
        const auto v6 = canonicalIpv6(std::string(text.substr(1, close - 1)));
        if (!v6) return std::nullopt;
        out.name = "[" + *v6 + "]";
        rest = text.substr(close + 1);
    } else {
        const auto colon = text.find(':');
        const std::string_view name = text.substr(0, colon);
        if (name.empty() || !std::all_of(name.begin(), name.end(), isNameChar)) return std::nullopt;
        out.name = lower(name);
        rest = colon == std::string_view::npos ? std::string_view() : text.substr(colon);
    }
    if (!parsePort(rest, out.port)) return std::nullopt;
    return out;
}

bool isLoopbackAddress(std::string_view host) {
    const std::string name = hostHeaderName(std::string(host));
    if (name == "localhost" || name == "[::1]") return true;
    return isIpv4(name) && name.rfind("127.", 0) == 0;
}

HostNames::HostNames(const std::string& boundHost, int port, const std::vector<std::string>& extra)
    : mPort(port) {
    const std::string bound = hostHeaderName(boundHost);
    if (bound.empty() || bound == "0.0.0.0" || bound == "[::]") {
        mBinding = Binding::Every;
        mOwnNames = {"localhost"};
    } else if (isLoopbackAddress(bound)) {
        mBinding = Binding::Loopback;
        mOwnNames = {"localhost", "127.0.0.1", "[::1]", bound};
    } else {
        mBinding = Binding::One;
        mOwnNames = {bound};
    }
    for (const std::string& name : extra) {
        const auto parsed = parseAuthority(name);
        if (!parsed)
            throw fit::InputError("allowed host '" + name.substr(0, 100) +
                                  "' is not a host name (NAME or NAME:PORT)");
        mExtra.push_back(*parsed);
    }
}

bool HostNames::answers(std::string_view hostHeader) const {
    const auto host = parseAuthority(hostHeader);
    if (!host) return false;
    for (const Authority& extra : mExtra)
        if (extra.name == host->name && (!extra.port || extra.port == host->port)) return true;
    if (host->port && *host->port != mPort) return false;
    if (std::find(mOwnNames.begin(), mOwnNames.end(), host->name) != mOwnNames.end()) return true;
    return mBinding == Binding::Every && (isIpv4(host->name) || host->name.front() == '[');
}

bool isSameOrigin(std::string_view origin, std::string_view hostHeader) {
    const std::string text = lower(origin);
    std::string_view authority(text);
    if (authority.rfind("http://", 0) == 0)
        authority.remove_prefix(7);
    else if (authority.rfind("https://", 0) == 0)
        authority.remove_prefix(8);
    else
        return false; // "null" (a sandboxed frame, a file: page) or another scheme
    const auto fromOrigin = parseAuthority(authority);
    const auto fromHost = parseAuthority(hostHeader);
    return fromOrigin && fromHost && sameAuthority(*fromOrigin, *fromHost);
}

} // namespace vots::server
