// Static file resolution that cannot leave the web folder, and the content types the viewer needs.
#include "routes/StaticFiles.h"

#include <algorithm>
#include <cctype>
#include <map>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

/// True when `inner` is `root` or below it (both canonical).
bool isInside(const fs::path& root, const fs::path& inner) {
    auto r = root.begin();
    auto i = inner.begin();
    for (; r != root.end(); ++r, ++i)
        if (i == inner.end() || *r != *i) return false;
    return true;
}

} // namespace

bool isHostileTarget(std::string_view target) {
    const std::string t = lower(target);
    for (const char* bad : {"..", "%2e%2e", "%2e.", ".%2e", "\\", "%5c", "%00", "%252e", "%255c", "%2500"})
        if (t.find(bad) != std::string::npos) return true;
    return t.find('\0') != std::string::npos;
}

std::string contentTypeFor(const fs::path& file) {
    static const std::map<std::string, std::string> TYPES{{".html", "text/html; charset=utf-8"},
                                                          {".js", "text/javascript; charset=utf-8"},
                                                          {".mjs", "text/javascript; charset=utf-8"},
                                                          {".css", "text/css; charset=utf-8"},
                                                          {".png", "image/png"},
                                                          {".svg", "image/svg+xml"},
                                                          {".json", "application/json"},
                                                          {".ico", "image/x-icon"}};
    const auto it = TYPES.find(lower(file.extension().string()));
    return it == TYPES.end() ? std::string() : it->second;
}

std::optional<fs::path> resolveStaticFile(const fs::path& webRoot, std::string_view urlPath) {
    if (webRoot.empty() || urlPath.empty() || urlPath[0] != '/') return std::nullopt;
    if (urlPath.find("..") != std::string_view::npos || urlPath.find('\\') != std::string_view::npos ||
        urlPath.find('\0') != std::string_view::npos)
        return std::nullopt;
    std::string relative(urlPath.substr(1));
    if (relative.empty() || relative.back() == '/') relative += "index.html";
    std::error_code ec;
    const fs::path root = fs::canonical(webRoot, ec);
    if (ec) return std::nullopt;
    const fs::path file = fs::canonical(root / relative, ec); // resolves symlinks: no escape through a link
    if (ec || !isInside(root, file) || !fs::is_regular_file(file, ec)) return std::nullopt;
    if (contentTypeFor(file).empty()) return std::nullopt;
    return file;
}

} // namespace vots::server
