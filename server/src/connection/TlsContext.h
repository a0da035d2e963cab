// TlsContext: the certificate and key HTTPS is served with (`vots serve --tls-cert/--tls-key`), re-read on
// demand (SIGHUP) while the connections already open keep the context they began with.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

struct ssl_ctx_st;
struct ssl_st;

namespace vots::server {

/// An OpenSSL connection object; freed (with its reference to the context) when the last owner goes.
using TlsSession = std::shared_ptr<ssl_st>;

class TlsContext {
public:
    /// Reads both files; throws fit::InputError naming the file and OpenSSL's reason when either cannot
    /// be read, or the key does not belong to the certificate.
    TlsContext(std::filesystem::path certificate, std::filesystem::path key);

    /// Reads both files again; on success new connections use them, on failure (thrown as above) the
    /// previous ones stay in force.
    void reload();

    /// A server-side session on the (non-blocking) socket fd, ready for its handshake; null when OpenSSL
    /// cannot make one.
    TlsSession accept(int fd) const;

private:
    const std::filesystem::path mCertificate, mKey;
    mutable std::mutex mMutex;
    std::shared_ptr<ssl_ctx_st> mContext; // TLS 1.2 or newer, OpenSSL's default ciphers
};

} // namespace vots::server
