// RequestHead: the text of an HTTP request head as the connection gate reads it: header names compared
// without case, values trimmed, where the head ends, and the client a trusted proxy forwards.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace vots::server {

bool equalsIgnoringCase(std::string_view a, std::string_view b);
/// Without leading and trailing blanks (and a trailing CR).
std::string_view trimmed(std::string_view s);
/// Where the head ends (just past its blank line), or npos. httplib accepts bare LF line ends too.
std::size_t headEnd(const std::string& bytes);
/// Removes the first "Expect: 100-continue" header line from a request whose head ends at headEnd(bytes).
void eraseExpectContinue(std::string& bytes);

/// The address the proxy itself saw, the last X-Forwarded-For entry (a proxy appends its peer to what the
/// client sent, so earlier entries may be forged), from a request head; nullopt when it has none or the
/// entry is not an IPv4 or IPv6 address.
std::optional<std::string> forwardedClient(std::string_view head);

} // namespace vots::server
