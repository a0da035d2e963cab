// GET /turntable: the /render parameters plus frames=N -> a VP9 WebM turn, its frames through the frame
// cache.
#include "HttpError.h"
#include "ServerImpl.h"
#include "frames/RenderFrames.h"
#include "vots/render/Png.h"
#include "vots/render/Turntable.h"
#include "vots/render/WebmWriter.h"

#include <cstdint>
#include <vector>

namespace vots::server {
namespace {

// One answer holds the whole video and is drawn while the client waits: bound the frames and the
// pixels so that one request stays within a minute or so of render-thread time and a few MB.
constexpr int MAX_FRAMES = 360;
constexpr int MAX_SIDE = 1024;
constexpr std::int64_t MAX_PIXELS = std::int64_t{MAX_FRAMES} * 512 * 512;

struct TurntableRequest {
    RenderParams first; // the first frame; the others turn its camera
    int frames = 0;
};

TurntableRequest parseTurntableRequest(QueryParams query) {
    TurntableRequest r;
    if (query.count("frames") != 1)
        throw HttpError(400, "give parameter 'frames' once: the views of the turn");
    const auto it = query.find("frames");
    const auto frames = render::parsePlainInt(it->second);
    if (!frames || *frames < 1 || *frames > MAX_FRAMES)
        throw HttpError(400, "frames must be a whole number in 1.." + std::to_string(MAX_FRAMES));
    r.frames = *frames;
    query.erase(it);
    r.first = parseRenderParams(query);
    r.first.client.clear(); // a turn's frames are never superseded by the same client's /render frames
    const int w = r.first.width, h = r.first.height;
    if (w < render::WEBM_MIN_SIDE || h < render::WEBM_MIN_SIDE || w > MAX_SIDE || h > MAX_SIDE)
        throw HttpError(400, "size for a turntable must be " + std::to_string(render::WEBM_MIN_SIDE) + ".." +
                                 std::to_string(MAX_SIDE) + " per side");
    if (std::int64_t{r.frames} * w * h > MAX_PIXELS)
        throw HttpError(400, "frames x width x height must be at most " + std::to_string(MAX_PIXELS) +
                                 " pixels (360 frames at 512x512)");
    return r;
}

} // namespace

void installTurntableRoute(Server::Impl& s) {
    s.http.Get("/turntable", [&s](const httplib::Request& req, httplib::Response& res) {
        // One place of the client's /render quota for the whole turn; its frames queue one at a time,
        // so other clients' frames are drawn in between.
        const ClientQuota::Ticket place = s.renders.enter(req.remote_addr);
        const TurntableRequest turn = parseTurntableRequest(targetQueryParams(req.target));
        const PreparedRender prepared =
            prepareRender(s, turn.first, req.remote_addr, s.guard.mayStartFits(req));

        render::WebmWriter video(turn.first.width, turn.first.height);
        int cached = 0;
        for (int k = 0; k < turn.frames; ++k) {
            RenderParams params = turn.first;
            params.camera = render::turntableCamera(turn.first.camera, turn.frames, k, std::nullopt);
            FrameCache::Source source = FrameCache::Source::Rendered;
            const auto frame = cachedFrame(s, prepared, params, &source);
            if (source == FrameCache::Source::Cached) ++cached;
            video.addFrame(
                render::decodePng(std::vector<std::uint8_t>(frame->png.begin(), frame->png.end())));
        }
        const std::vector<std::uint8_t> webm = video.finish();
        res.status = 200;
        res.set_header("X-Vots-Frames", std::to_string(turn.frames));
        res.set_header("X-Vots-Frame-Cache-Hits", std::to_string(cached));
        res.set_header("Content-Disposition", "inline; filename=\"" + turn.first.dataset + "-turn.webm\"");
        res.set_header("Cache-Control", "no-cache");
        res.set_content(std::string(webm.begin(), webm.end()), "video/webm");
    });
}

} // namespace vots::server
