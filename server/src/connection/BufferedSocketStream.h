// BufferedSocketStream: the httplib::Stream a worker serves a gated request through: the bytes the
// ConnectionGate read first, then the socket itself (through its TLS session for HTTPS), with time limits
// on every wait.
#pragma once

#include "connection/ConnectionGate.h"

#include <httplib.h>

#include <chrono>
#include <string>

namespace vots::server {

class BufferedSocketStream final : public httplib::Stream {
public:
    /// Does not own the socket. timeout: the longest wait for the socket to become readable or writable.
    BufferedSocketStream(const ArrivedRequest& request, std::chrono::milliseconds timeout);

    bool is_readable() const override;
    bool is_writable() const override;
    ssize_t read(char* ptr, std::size_t size) override;
    using httplib::Stream::write;
    ssize_t write(const char* ptr, std::size_t size) override;
    void get_remote_ip_and_port(std::string& ip, int& port) const override;
    void get_local_ip_and_port(std::string& ip, int& port) const override;
    socket_t socket() const override { return mRequest.fd; }

    /// HTTPS: sends close_notify (best effort); the socket stays open. Nothing for plain HTTP.
    void shutdownTls();

private:
    bool waitFor(short events) const;
    template <typename Transfer> ssize_t throughTls(Transfer transfer);

    const ArrivedRequest& mRequest;
    const std::chrono::milliseconds mTimeout;
    std::size_t mOffset = 0; // into mRequest.bytes
};

} // namespace vots::server
