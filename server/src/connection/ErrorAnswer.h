// The JSON error answer a connection gets when it is refused before any handler, sent at once.
#pragma once

#include <string>
#include <string_view>

struct ssl_st;

namespace vots::server {

/// A complete JSON error answer, with Connection: close.
std::string jsonErrorAnswer(int status, const std::string& message);
/// Writes bytes at once to a plain socket, or through `tls` when it is set; best effort, never blocks on a
/// non-blocking socket (the few hundred bytes of an answer fit in any empty send buffer).
void sendBytesNow(int fd, ssl_st* tls, std::string_view bytes);
/// Writes jsonErrorAnswer() at once, as sendBytesNow().
void sendJsonErrorNow(int fd, int status, const std::string& message, ssl_st* tls = nullptr);

} // namespace vots::server
