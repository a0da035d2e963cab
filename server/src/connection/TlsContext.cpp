// TlsContext: an OpenSSL server context built from PEM files, swapped whole on reload.
#include "connection/TlsContext.h"

#include "vots/fit/Error.h"

#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>

#include <csignal>

namespace vots::server {
namespace {

/// OpenSSL's reason for the last failure, its error queue emptied.
std::string lastOpenSslError() {
    const unsigned long code = ERR_get_error();
    ERR_clear_error();
    if (code == 0) return "unknown error";
    char text[256] = {};
    ERR_error_string_n(code, text, sizeof text);
    return text;
}

std::shared_ptr<ssl_ctx_st> contextFrom(const std::filesystem::path& certificate,
                                        const std::filesystem::path& key) {
    ERR_clear_error();
    std::shared_ptr<ssl_ctx_st> context(SSL_CTX_new(TLS_server_method()), SSL_CTX_free);
    if (!context) throw fit::InputError("cannot create a TLS context: " + lastOpenSslError());
    SSL_CTX_set_min_proto_version(context.get(), TLS1_2_VERSION);
    // A worker's write may be retried after a partial send (the sockets are non-blocking).
    SSL_CTX_set_mode(context.get(), SSL_MODE_ENABLE_PARTIAL_WRITE | SSL_MODE_ACCEPT_MOVING_WRITE_BUFFER);
    SSL_CTX_set_options(context.get(), SSL_OP_NO_RENEGOTIATION | SSL_OP_CIPHER_SERVER_PREFERENCE);
    if (SSL_CTX_use_certificate_chain_file(context.get(), certificate.c_str()) != 1)
        throw fit::InputError("cannot read the TLS certificate '" + certificate.string() +
                              "': " + lastOpenSslError());
    const bool keyRead = SSL_CTX_use_PrivateKey_file(context.get(), key.c_str(), SSL_FILETYPE_PEM) == 1;
    // OpenSSL compares the key with the certificate as it reads it.
    const bool mismatch = !keyRead && ERR_GET_REASON(ERR_peek_last_error()) == X509_R_KEY_VALUES_MISMATCH;
    if (!keyRead && !mismatch)
        throw fit::InputError("cannot read the TLS key '" + key.string() + "': " + lastOpenSslError());
    if (mismatch || SSL_CTX_check_private_key(context.get()) != 1) {
        ERR_clear_error();
        throw fit::InputError("the TLS key '" + key.string() + "' does not belong to the certificate '" +
                              certificate.string() + "'");
    }
    return context;
}

} // namespace

TlsContext::TlsContext(std::filesystem::path certificate, std::filesystem::path key)
    : mCertificate(std::move(certificate)), mKey(std::move(key)), mContext(contextFrom(mCertificate, mKey)) {
    // OpenSSL writes to its sockets with write(2), which raises SIGPIPE (ending the process) when a
    // client has gone; the plain paths send with MSG_NOSIGNAL instead.
    std::signal(SIGPIPE, SIG_IGN);
}

void TlsContext::reload() {
    auto fresh = contextFrom(mCertificate, mKey);
    std::lock_guard lock(mMutex);
    mContext = std::move(fresh);
}

TlsSession TlsContext::accept(int fd) const {
    std::shared_ptr<ssl_ctx_st> context;
    {
        std::lock_guard lock(mMutex);
        context = mContext;
    }
    // SSL_new takes its own reference to the context: a reload never frees one a connection uses.
    TlsSession session(SSL_new(context.get()), SSL_free);
    if (!session || SSL_set_fd(session.get(), fd) != 1) return nullptr;
    SSL_set_accept_state(session.get());
    return session;
}

} // namespace vots::server
