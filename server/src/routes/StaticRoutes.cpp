// Serving the viewer's files from the web folder (called from the pre-routing step for non-API paths).
#include "routes/HttpJson.h"
#include "ServerImpl.h"
#include "routes/StaticFiles.h"

#include <fstream>
#include <sstream>

namespace vots::server {

bool serveStatic(const Server::Impl& s, const httplib::Request& req, httplib::Response& res) {
    const auto file = resolveStaticFile(s.options.webDir, req.path);
    if (!file) return false;
    std::ifstream in(*file, std::ios::binary);
    if (!in) return false;
    std::ostringstream bytes;
    bytes << in.rdbuf();
    res.status = 200;
    res.set_header("Cache-Control", "no-cache"); // the viewer changes while we develop; revalidate
    res.set_content(bytes.str(), contentTypeFor(*file).c_str());
    return true;
}

} // namespace vots::server
