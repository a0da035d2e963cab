// RequestHead: reading the text of a request head (header names, values, its end) as the gate needs it.
#include "connection/RequestHead.h"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <algorithm>
#include <cctype>

namespace vots::server {
namespace {

bool isIpAddress(const std::string& text) {
    in6_addr buffer{};
    return ::inet_pton(AF_INET, text.c_str(), &buffer) == 1 ||
           ::inet_pton(AF_INET6, text.c_str(), &buffer) == 1;
}

} // namespace

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

/// Where the head ends (just past its blank line), or npos. httplib accepts bare LF line ends too.
std::size_t headEnd(const std::string& bytes) {
    const std::size_t crlf = bytes.find("\r\n\r\n");
    const std::size_t lf = bytes.find("\n\n");
    if (crlf == std::string::npos && lf == std::string::npos) return std::string::npos;
    if (lf == std::string::npos || (crlf != std::string::npos && crlf < lf)) return crlf + 4;
    return lf + 2;
}

// Removes "Expect: 100-continue" header lines from a request whose head ends at headEnd(bytes).
void eraseExpectContinue(std::string& bytes) {
    const std::size_t end = headEnd(bytes);
    if (end == std::string::npos) return;
    std::size_t pos = bytes.find('\n');
    while (pos != std::string::npos && pos + 1 < end) {
        const std::size_t start = pos + 1;
        const std::size_t next = bytes.find('\n', start);
        const std::size_t lineEnd = next == std::string::npos || next > end ? end : next + 1;
        const std::string_view line(bytes.data() + start, (next == std::string::npos ? end : next) - start);
        const std::size_t colon = line.find(':');
        if (colon != std::string_view::npos && equalsIgnoringCase(trimmed(line.substr(0, colon)), "Expect") &&
            equalsIgnoringCase(trimmed(line.substr(colon + 1)), "100-continue")) {
            bytes.erase(start, lineEnd - start);
            return; // one such line; a second one is the handler's to refuse
        }
        pos = next;
    }
}

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
        if (colon == std::string_view::npos ||
            !equalsIgnoringCase(trimmed(line.substr(0, colon)), "X-Forwarded-For"))
            continue;
        const std::string_view value = line.substr(colon + 1);
        const std::size_t comma = value.rfind(',');
        last = std::string(trimmed(comma == std::string_view::npos ? value : value.substr(comma + 1)));
    }
    if (!last || !isIpAddress(*last)) return std::nullopt;
    return last;
}

} // namespace vots::server
