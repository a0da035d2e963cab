// Safe mapping of a URL path to a file inside the web folder, and content types; no HTTP types.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace vots::server {

/// True when the raw request target (before percent-decoding) holds "..", an encoded dot pair,
/// a backslash (raw or %5c), or a NUL (raw or %00): such requests are refused outright.
bool isHostileTarget(std::string_view target);

/// The file for a decoded URL path ("/" -> index.html) if it exists inside webRoot (after resolving
/// symlinks) and is a regular file of a served type; nullopt otherwise.
std::optional<std::filesystem::path> resolveStaticFile(const std::filesystem::path& webRoot,
                                                       std::string_view urlPath);

/// "text/html; charset=utf-8", "text/javascript", ... for html/js/mjs/css/png/svg/json/ico; empty if not
/// served.
std::string contentTypeFor(const std::filesystem::path& file);

} // namespace vots::server
