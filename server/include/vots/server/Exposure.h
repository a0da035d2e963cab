// What serving beyond loopback needs: telling loopback addresses apart, and the access token's sources.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vots::server {

/// True for "localhost", 127.x.y.z and ::1: a server bound there is reachable from this machine only.
bool isLoopbackHost(const std::string& host);

/// A fresh access token: 128 bits from std::random_device (the kernel's generator), as 32 hex digits.
std::string generateAccessToken();

/// What a token may do (docs/API.md, "Security"): a viewer lists, renders, searches and retrieves from the
/// PACS; an operator also starts fits and stores to the PACS.
enum class Role { Viewer, Operator };
std::string_view roleName(Role role);

/// One token of the token file: whose it is (logged and answered; the token never is) and its role.
struct AccessToken {
    std::string name;
    Role role = Role::Operator;
    std::string token;
};

/// The tokens a file holds: one bare token (an operator named "operator", as before roles), or lines
/// "NAME ROLE TOKEN" (ROLE viewer or operator; blank lines and lines from '#' on skipped). Throws
/// fit::InputError when the file cannot be read, a line is malformed, a name or token repeats, or a
/// token is not 16..256 of letters, digits and - . _ ~ + / = (those a Bearer token may have); the
/// message never quotes a token.
std::vector<AccessToken> readAccessTokenFile(const std::filesystem::path& file);

} // namespace vots::server
