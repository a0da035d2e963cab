// Every request in hostile/*.http, sent as raw bytes, must get its expected 4xx with a JSON error body.
#include "ServerFixture.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>

namespace vots::test {
namespace {

namespace fs = std::filesystem;

/// File format: optional "# expect NNN" line, then the request line, optional header lines, and after
/// a blank line an optional body. {{C*N}} expands to N copies of character C and {{NUL}} to a zero
/// byte. Host, Connection: close and (with a body) Content-Length are added.
struct HostileRequest {
    int expect = 0;
    std::string bytes;
};

std::string expand(const std::string& text) {
    static const std::regex repeat(R"(\{\{(.)\*(\d+)\}\})");
    std::string out;
    std::sregex_iterator it(text.begin(), text.end(), repeat);
    std::size_t last = 0;
    for (; it != std::sregex_iterator(); ++it) {
        out += text.substr(last, static_cast<std::size_t>(it->position()) - last);
        out += std::string(std::stoul((*it)[2].str()), (*it)[1].str()[0]);
        last = static_cast<std::size_t>(it->position() + it->length());
    }
    out += text.substr(last);
    // Copied piece by piece rather than with std::string::replace, which GCC 12 warns about wrongly
    // (-Wrestrict) at -O2.
    const std::string nul = "{{NUL}}";
    std::string withNul;
    for (std::size_t pos = 0;;) {
        const std::size_t next = out.find(nul, pos);
        withNul.append(out, pos, next == std::string::npos ? std::string::npos : next - pos);
        if (next == std::string::npos) return withNul;
        withNul.push_back('\0');
        pos = next + nul.size();
    }
}

HostileRequest loadHostile(const fs::path& file) {
    std::string text = fileBytes(file.string());
    HostileRequest r;
    if (text.rfind("# expect ", 0) == 0) {
        r.expect = std::stoi(text.substr(9, 3));
        text = text.substr(text.find('\n') + 1);
    }
    const auto blank = text.find("\n\n");
    std::string head = text.substr(0, blank == std::string::npos ? text.size() : blank);
    std::string body = blank == std::string::npos ? "" : text.substr(blank + 2);
    while (!head.empty() && head.back() == '\n')
        head.pop_back();
    if (!body.empty() && body.back() == '\n') body.pop_back();
    head = expand(head);
    body = expand(body);
    std::string bytes;
    std::istringstream lines(head);
    for (std::string line; std::getline(lines, line);)
        bytes += line + "\r\n";
    bytes += "Host: 127.0.0.1\r\nConnection: close\r\n";
    if (!body.empty())
        bytes += "Content-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) + "\r\n";
    r.bytes = bytes + "\r\n" + body;
    return r;
}

/// True once the head and Content-Length bytes of body have arrived. (After a 414 httplib has not seen
/// our "Connection: close" and would keep the connection open until its keep-alive timeout.)
bool isComplete(const std::string& answer) {
    const auto headEnd = answer.find("\r\n\r\n");
    if (headEnd == std::string::npos) return false;
    const auto length = answer.find("Content-Length: ");
    if (length == std::string::npos || length > headEnd) return false;
    return answer.size() >= headEnd + 4 + std::stoul(answer.substr(length + 16));
}

/// Sends raw bytes and reads one whole answer.
std::string exchange(int port, const std::string& request) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{60, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    std::string answer;
    if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
        // The server may answer (413, 414) and close before it has read everything: ignore send errors.
        for (std::size_t sent = 0; sent < request.size();) {
            const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
            if (n <= 0) break;
            sent += static_cast<std::size_t>(n);
        }
        char buffer[4096];
        for (ssize_t n; !isComplete(answer) && (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;)
            answer.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fd);
    return answer;
}

class ServerHostile : public SharedServerTest {};

TEST_F(ServerHostile, CorpusGetsExpected4xxWithJsonError) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(VOTS_HOSTILE_DIR))
        if (entry.path().extension() == ".http") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    ASSERT_GE(files.size(), 20u);
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.filename().string());
        const HostileRequest request = loadHostile(file);
        const std::string answer = exchange(sServer->port(), request.bytes);
        ASSERT_GE(answer.size(), 12u) << "no answer";
        const int status = std::stoi(answer.substr(9, 3));
        EXPECT_GE(status, 400);
        EXPECT_LT(status, 500);
        if (request.expect) {
            EXPECT_EQ(status, request.expect);
        }
        const auto headEnd = answer.find("\r\n\r\n");
        ASSERT_NE(headEnd, std::string::npos);
        EXPECT_NE(answer.substr(0, headEnd).find("Content-Type: application/json"), std::string::npos);
        const auto json = nlohmann::json::parse(answer.substr(headEnd + 4), nullptr, false);
        ASSERT_FALSE(json.is_discarded()) << answer.substr(0, 300);
        EXPECT_TRUE(json.contains("error") && json["error"].is_string());
    }
    // And the server is still fine afterwards.
    const auto res = client()->Get("/api/datasets");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200);
}

} // namespace
} // namespace vots::test
