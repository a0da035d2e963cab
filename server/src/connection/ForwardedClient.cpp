// forwardedClient: the last X-Forwarded-For entry of a request head, when it is an IP address.
#include "connection/ForwardedClient.h"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <algorithm>
#include <cctype>

namespace vots::server {
namespace {

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

bool isForwardedFor(std::string_view name) {
    constexpr std::string_view wanted = "x-forwarded-for";
    return name.size() == wanted.size() &&
           std::equal(name.begin(), name.end(), wanted.begin(),
                      [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

bool isIpAddress(const std::string& text) {
    in6_addr buffer{};
    return ::inet_pton(AF_INET, text.c_str(), &buffer) == 1 ||
           ::inet_pton(AF_INET6, text.c_str(), &buffer) == 1;
}

} // namespace

std::optional<std::string> forwardedClient(std::string_view head) {
    std::optional<std::string> last;
    std::size_t pos = head.find('\n'); // past the request line
    while (pos != std::string_view::npos && pos + 1 < head.size()) {
        const std::size_t start = pos + 1;
        pos = head.find('\n', start);
        const std::string_view line =
            trimmed(head.substr(start, pos == std::string_view::npos ? pos : pos - start));
        if (line.empty()) break; // the head's end
        const std::size_t colon = line.find(':');
        if (colon == std::string_view::npos || !isForwardedFor(trimmed(line.substr(0, colon)))) continue;
        const std::string_view value = line.substr(colon + 1);
        const std::size_t comma = value.rfind(',');
        last = std::string(trimmed(comma == std::string_view::npos ? value : value.substr(comma + 1)));
    }
    if (!last || !isIpAddress(*last)) return std::nullopt;
    return last;
}

} // namespace vots::server
