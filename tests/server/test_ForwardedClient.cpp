// forwardedClient: only the last X-Forwarded-For entry (the one the trusted proxy wrote) counts.
#include "connection/RequestHead.h"

#include <gtest/gtest.h>

namespace vots::server {
namespace {

TEST(ForwardedClient, TakesTheLastEntryThatTheProxyAppended) {
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nHost: a\r\nX-Forwarded-For: 10.0.0.7\r\n\r\n"), "10.0.0.7");
    // A client's own (forged) entries come first; the proxy appends the address it saw.
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nx-forwarded-for: 1.2.3.4, 10.0.0.7\r\n\r\n"), "10.0.0.7");
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nX-Forwarded-For: 1.2.3.4\r\nX-Forwarded-For: ::1\r\n\r\n"),
              "::1");
}

TEST(ForwardedClient, NoneWithoutAnAddress) {
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nHost: a\r\n\r\n"), std::nullopt);
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nX-Forwarded-For: unknown\r\n\r\n"), std::nullopt);
    EXPECT_EQ(forwardedClient("GET / HTTP/1.1\r\nX-Forwarded-For: \r\n\r\n"), std::nullopt);
    // Headers after the head's end are body bytes.
    EXPECT_EQ(forwardedClient("POST / HTTP/1.1\r\n\r\nX-Forwarded-For: 10.0.0.7\r\n"), std::nullopt);
}

} // namespace
} // namespace vots::server
