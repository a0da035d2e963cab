// Which Host headers and Origins are the server's own (DNS rebinding, cross-site requests); no HTTP types.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vots::server {

/// A Host header or an Origin's authority taken apart: the name lower-cased (an IPv6 address keeps
/// its brackets), and the port when one is written.
struct Authority {
    std::string name;
    std::optional<int> port;
};

/// "name", "name:port", "[v6]" or "[v6]:port"; nullopt for anything else (empty, bad port, spaces, ...).
std::optional<Authority> parseAuthority(std::string_view text);

/// True for "localhost", a 127.x.y.z address and "::1" (with or without brackets).
bool isLoopbackAddress(std::string_view host);

/// The Host names a server bound to `boundHost`:`port` answers. A browser always sends the name of
/// the URL it loads, so a page of another site that a rebound DNS name points at us arrives with that
/// site's name, which is in none of these lists:
/// - bound to loopback: localhost, 127.0.0.1, [::1] and the bound name;
/// - bound to one address or name: that one;
/// - bound to every interface (0.0.0.0, ::): any IP address written as such, since DNS rebinding needs
///   a name (a URL with an address is the address's own origin);
/// plus the `extra` names (--allow-host): "name" at any port (a reverse proxy forwards its own Host),
/// "name:port" at that port only.
class HostNames {
public:
    HostNames() = default;
    /// Throws fit::InputError naming an extra entry that is not a host name.
    HostNames(const std::string& boundHost, int port, const std::vector<std::string>& extra);

    /// True when the Host header names this server. A port, when written, must be the bound one; one
    /// not written is accepted, as browsers write every port but 80 (so no page of ours omits it).
    bool answers(std::string_view hostHeader) const;

private:
    enum class Binding { Loopback, One, Every };
    Binding mBinding = Binding::Loopback;
    int mPort = 0;
    std::vector<std::string> mOwnNames; // at the bound port
    std::vector<Authority> mExtra;
};

/// True when `origin` ("http://host:port", as browsers send it) is the origin of a page served under
/// `hostHeader`: the same authority, over http or https (https: behind a TLS proxy).
bool isSameOrigin(std::string_view origin, std::string_view hostHeader);

} // namespace vots::server
