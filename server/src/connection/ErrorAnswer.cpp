// The JSON error answers of refused connections: their status line, their body, and sending them at once.
#include "connection/ErrorAnswer.h"

#include <nlohmann/json.hpp>
#include <openssl/err.h>
#include <openssl/ssl.h>

#include <sys/socket.h>

namespace vots::server {
namespace {

const char* reasonPhrase(int status) {
    switch (status) {
    case 400:
        return "Bad Request";
    case 411:
        return "Length Required";
    case 414:
        return "URI Too Long";
    case 431:
        return "Request Header Fields Too Large";
    case 503:
        return "Service Unavailable";
    default:
        return "Error";
    }
}

} // namespace

std::string jsonErrorAnswer(int status, const std::string& message) {
    const std::string body = nlohmann::json{{"error", message}}.dump();
    return "HTTP/1.1 " + std::to_string(status) + " " + reasonPhrase(status) +
           "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
           "\r\nConnection: close\r\n\r\n" + body;
}

void sendBytesNow(int fd, ssl_st* tls, std::string_view bytes) {
    if (tls) {
        ERR_clear_error();
        [[maybe_unused]] const int sent = SSL_write(tls, bytes.data(), static_cast<int>(bytes.size()));
        ERR_clear_error();
        return;
    }
    [[maybe_unused]] const ssize_t sent = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

void sendJsonErrorNow(int fd, int status, const std::string& message, ssl_st* tls) {
    sendBytesNow(fd, tls, jsonErrorAnswer(status, message));
}

} // namespace vots::server
