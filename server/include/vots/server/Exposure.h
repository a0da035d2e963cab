// What serving beyond loopback needs: telling loopback addresses apart, and the access token's sources.
#pragma once

#include <filesystem>
#include <string>

namespace vots::server {

/// True for "localhost", 127.x.y.z and ::1: a server bound there is reachable from this machine only.
bool isLoopbackHost(const std::string& host);

/// A fresh access token: 128 bits from std::random_device (the kernel's generator), as 32 hex digits.
std::string generateAccessToken();

/// The token a file holds: its content without leading and trailing white space. Throws
/// fit::InputError when the file cannot be read, or the token is shorter than 16 characters or has
/// characters other than letters, digits and - . _ ~ + / = (those a Bearer token may have).
std::string readAccessTokenFile(const std::filesystem::path& file);

} // namespace vots::server
