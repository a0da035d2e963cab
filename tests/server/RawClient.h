// Raw TCP clients for the connection tests: sockets that connect from a chosen loopback address (all of
// 127/8 is loopback on Linux, so each address is a distinct "client") and send exactly what a test says.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace vots::test {

/// A connected socket from source (e.g. "127.0.0.2") to 127.0.0.1:port, or -1.
inline int connectFrom(const std::string& source, int port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) return -1;
    sockaddr_in from{};
    from.sin_family = AF_INET;
    ::inet_pton(AF_INET, source.c_str(), &from.sin_addr);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&from), sizeof from) != 0 ||
        ::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
        ::close(fd);
        return -1;
    }
    return fd;
}

inline bool sendAll(int fd, const std::string& bytes) {
    for (std::size_t sent = 0; sent < bytes.size();) {
        const ssize_t n = ::send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) return false;
        sent += static_cast<std::size_t>(n);
    }
    return true;
}

/// Reads until the server closes, `until` bytes have come, or nothing came for `quiet`.
inline std::string receive(int fd, std::chrono::milliseconds quiet, std::size_t until = std::string::npos) {
    std::string answer;
    char buffer[8192];
    while (answer.size() < until) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(quiet.count())) <= 0) break;
        const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        answer.append(buffer, static_cast<std::size_t>(n));
    }
    return answer;
}

/// A GET (or a POST with a JSON body) as a browser would send it, Connection: close.
inline std::string requestText(const std::string& method, const std::string& target, int port,
                               const std::string& jsonBody = {}) {
    std::string text = method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                       "\r\nConnection: close\r\n";
    if (!jsonBody.empty())
        text +=
            "Content-Type: application/json\r\nContent-Length: " + std::to_string(jsonBody.size()) + "\r\n";
    return text + "\r\n" + jsonBody;
}

struct RawAnswer {
    int status = 0; // 0: no answer
    std::string headers;
    std::string body;
};

/// One whole exchange from the source address; waits at most `wait` for the answer.
inline RawAnswer exchangeFrom(const std::string& source, int port, const std::string& request,
                              std::chrono::milliseconds wait = std::chrono::seconds(60)) {
    RawAnswer answer;
    const int fd = connectFrom(source, port);
    if (fd < 0) return answer;
    std::string text;
    if (sendAll(fd, request)) text = receive(fd, wait);
    ::close(fd);
    const std::size_t headEnd = text.find("\r\n\r\n");
    if (text.rfind("HTTP/1.1 ", 0) != 0 || headEnd == std::string::npos) return answer;
    answer.status = std::stoi(text.substr(9, 3));
    answer.headers = text.substr(0, headEnd);
    answer.body = text.substr(headEnd + 4);
    return answer;
}

} // namespace vots::test
