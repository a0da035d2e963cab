// The client a trusted reverse proxy (`vots serve --behind-proxy ADDR`) names in X-Forwarded-For.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace vots::server {

/// The address the proxy itself saw, the last X-Forwarded-For entry (a proxy appends its peer to what the
/// client sent, so earlier entries may be forged), from a request head; nullopt when it has none or the
/// entry is not an IPv4 or IPv6 address.
std::optional<std::string> forwardedClient(std::string_view head);

} // namespace vots::server
