// GET /render: parse, find the dataset, wait for its Vot-Space (fitting if needed), render on the GL thread.
#include "HttpError.h"
#include "ServerImpl.h"
#include "frames/RenderFrames.h"
#include "routes/HttpJson.h"

#include <cstdio>

namespace vots::server {
namespace {

std::string formatMs(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

} // namespace

void installRenderRoute(Server::Impl& s) {
    s.http.Get("/render", [&s](const httplib::Request& req, httplib::Response& res) {
        // Held until the answer is made: one client cannot fill the render queue for everyone.
        const ClientQuota::Ticket place = s.renders.enter(req.remote_addr);
        const RenderParams params = parseRenderParams(targetQueryParams(req.target));
        const PreparedRender prepared = prepareRender(s, params, req.remote_addr, s.guard.mayStartFits(req));

        FrameCache::Source source = FrameCache::Source::Rendered;
        const auto frame = cachedFrame(s, prepared, params, &source);
        res.status = 200;
        res.set_header("X-Vots-Vot-Count", std::to_string(frame->votCount));
        res.set_header("X-Vots-Frame-Ms", formatMs(frame->frameMs));
        res.set_header("X-Vots-Upload-Ms", formatMs(frame->uploadMs));
        res.set_header("X-Vots-Encode-Ms", formatMs(frame->encodeMs));
        res.set_header("X-Vots-Frame-Cache", std::string(fit::nameOf(source)));
        res.set_header("X-Vots-Fit-Seconds", formatMs(frame->fitSeconds));
        res.set_header("Cache-Control", "no-cache");
        res.set_content(frame->png, "image/png");
    });
}

} // namespace vots::server
