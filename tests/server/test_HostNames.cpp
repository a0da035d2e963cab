// HostNames, Origin matching, the constant-time token comparison and the token file's rules.
#include "TempDir.h"
#include "security/HostNames.h"
#include "security/RequestGuard.h"
#include "vots/fit/Error.h"
#include "vots/server/Exposure.h"

#include <gtest/gtest.h>

#include <set>

namespace vots::server {
namespace {

TEST(HostNames, ParsesNamesAddressesAndPorts) {
    const auto named = parseAuthority("LocalHost:8080");
    ASSERT_TRUE(named);
    EXPECT_EQ(named->name, "localhost");
    EXPECT_EQ(named->port, 8080);
    const auto v6 = parseAuthority("[0:0::1]:80");
    ASSERT_TRUE(v6);
    EXPECT_EQ(v6->name, "[::1]");
    EXPECT_EQ(v6->port, 80);
    EXPECT_FALSE(parseAuthority("plain")->port);
    for (const char* bad : {"", ":80", "a:", "a:0", "a:65536", "a:80x", "a b", "::1", "[::1", "[nope]:1",
                            "a:80:80", "evil.example/x", "a@b"})
        EXPECT_FALSE(parseAuthority(bad)) << bad;
}

TEST(HostNames, LoopbackAnswersLoopbackNamesAtItsPortOnly) {
    const HostNames hosts("127.0.0.1", 8080, {});
    for (const char* ok : {"127.0.0.1:8080", "localhost:8080", "LOCALHOST:8080", "[::1]:8080", "127.0.0.1"})
        EXPECT_TRUE(hosts.answers(ok)) << ok;
    for (const char* refused : {"evil.example", "evil.example:8080", "127.0.0.1:8081", "localhost:80",
                                "127.0.0.1.evil.example:8080", "192.168.1.5:8080", "", "[::1]:8081"})
        EXPECT_FALSE(hosts.answers(refused)) << refused;
}

TEST(HostNames, OneAddressAnswersItsNameAndTheExtras) {
    const HostNames hosts("192.168.1.5", 9000, {"vots.lan", "Proxy.Lan:443"});
    EXPECT_TRUE(hosts.answers("192.168.1.5:9000"));
    EXPECT_FALSE(hosts.answers("192.168.1.6:9000"));
    EXPECT_FALSE(hosts.answers("localhost:9000")); // not reachable as localhost when bound elsewhere
    EXPECT_TRUE(hosts.answers("vots.lan"));        // an extra NAME: any port
    EXPECT_TRUE(hosts.answers("vots.lan:12345"));
    EXPECT_TRUE(hosts.answers("proxy.lan:443")); // NAME:PORT: that port only
    EXPECT_FALSE(hosts.answers("proxy.lan:80"));
    EXPECT_FALSE(hosts.answers("proxy.lan"));
    EXPECT_FALSE(hosts.answers("evil.example:9000"));
    EXPECT_THROW(HostNames("127.0.0.1", 1, {"not a name"}), fit::InputError);
}

TEST(HostNames, EveryInterfaceAnswersAddressesButNoForeignName) {
    for (const char* wildcard : {"0.0.0.0", "::"}) {
        SCOPED_TRACE(wildcard);
        const HostNames hosts(wildcard, 8080, {});
        for (const char* ok : {"10.1.2.3:8080", "[fe80::1]:8080", "127.0.0.1:8080", "localhost:8080"})
            EXPECT_TRUE(hosts.answers(ok)) << ok;
        for (const char* refused : {"evil.example:8080", "10.1.2.3:8081", "10.1.2.3.nip.example:8080"})
            EXPECT_FALSE(hosts.answers(refused)) << refused;
    }
}

TEST(HostNames, SameOriginIsTheHostOverHttpOrHttps) {
    EXPECT_TRUE(isSameOrigin("http://127.0.0.1:8080", "127.0.0.1:8080"));
    EXPECT_TRUE(isSameOrigin("HTTP://LocalHost:8080", "localhost:8080"));
    EXPECT_TRUE(isSameOrigin("https://proxy.lan", "proxy.lan"));
    for (const char* foreign : {"http://evil.example", "http://127.0.0.1:8081", "http://localhost:8080",
                                "null", "file://", "http://127.0.0.1:8080/path", ""})
        EXPECT_FALSE(isSameOrigin(foreign, "127.0.0.1:8080")) << foreign;
    EXPECT_FALSE(isSameOrigin("http://127.0.0.1:8080", "")); // an Origin with no Host to match
}

TEST(HostNames, LoopbackHosts) {
    for (const char* host : {"127.0.0.1", "127.1.2.3", "localhost", "::1", "[::1]"})
        EXPECT_TRUE(isLoopbackHost(host)) << host;
    for (const char* host : {"0.0.0.0", "::", "192.168.1.5", "myhost", "128.0.0.1", "localhost.example"})
        EXPECT_FALSE(isLoopbackHost(host)) << host;
}

TEST(AccessToken, ComparesWholeTokens) {
    EXPECT_TRUE(tokensEqual("abcdef0123456789", "abcdef0123456789"));
    for (const char* wrong :
         {"", "abcdef012345678", "abcdef01234567890", "Abcdef0123456789", "abcdef012345678X"})
        EXPECT_FALSE(tokensEqual(wrong, "abcdef0123456789")) << wrong;
    EXPECT_FALSE(tokensEqual(std::string_view("abcdef0123456789\0", 17), "abcdef0123456789"));
}

TEST(AccessToken, GeneratedTokensAre128BitsOfHexAndDiffer) {
    std::set<std::string> seen;
    for (int i = 0; i < 20; ++i) {
        const std::string token = generateAccessToken();
        EXPECT_EQ(token.size(), 32u);
        EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
        seen.insert(token);
    }
    EXPECT_EQ(seen.size(), 20u);
}

TEST(AccessToken, TokenFileIsTrimmedAndChecked) {
    test::TempDir dir;
    dir.write("good", "  s3cret-Token_0123456789~+/=\n\n");
    const auto good = readAccessTokenFile(dir.path() / "good");
    ASSERT_EQ(good.size(), 1u);
    EXPECT_EQ(good[0].token, "s3cret-Token_0123456789~+/=");
    EXPECT_EQ(good[0].role, Role::Operator);
    dir.write("short", "zqxw\n");
    dir.write("empty", "\n");
    dir.write("space", "zqxwzqxw zqxwzqxwzqxw\n");
    dir.write("quote", "zqxwzqxwzqxwzqxwzqxw\"\n");
    for (const char* bad : {"short", "empty", "space", "quote", "missing"}) {
        SCOPED_TRACE(bad);
        try {
            readAccessTokenFile(dir.path() / bad);
            ADD_FAILURE() << "accepted";
        } catch (const fit::InputError& e) {
            EXPECT_EQ(std::string(e.what()).find("zqxw"), std::string::npos)
                << "quotes the content: " << e.what();
        }
    }
}

} // namespace
} // namespace vots::server
