// GET /render: parse, find the dataset, wait for its Vot-Space (fitting if needed), render on the GL thread.
#include "CacheMeta.h"
#include "HttpError.h"
#include "HttpJson.h"
#include "ServerImpl.h"
#include "vots/render/CameraText.h"
#include "vots/render/Colormap.h"
#include "vots/render/Png.h"

#include <chrono>
#include <cstdio>

namespace vots::server {
namespace {

constexpr auto FIT_WAIT = std::chrono::minutes(10); // a /render waits this long for its fit at most

std::string formatMs(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

// Text that reads back as the same float (9 significant digits): windows share a key only when equal.
std::string exactText(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
    return text;
}

/// Everything the image depends on: what it is drawn from (the Vot-Space's fit key, or the volume),
/// camera, size, mode, renderer, slab, window and colour map; not the client id.
std::string frameKeyFor(const std::string& drawnFrom, const RenderParams& p) {
    std::string key = drawnFrom;
    key += '|' + render::formatCamera(p.camera) + '|' + std::to_string(p.width) + 'x' +
           std::to_string(p.height) + '|' + std::string(render::renderModeName(p.mode)) + '|' +
           std::string(render::rendererName(p.renderer)) + '|' + (p.slab ? render::formatSlab(*p.slab) : "") +
           '|' + std::string(render::colormapName(p.colormap)) + '|';
    key += p.window ? exactText(p.window->level) + ',' + exactText(p.window->width) : "auto";
    return key;
}

const char* sourceName(FrameCache::Source source) {
    switch (source) {
    case FrameCache::Source::Rendered:
        return "miss";
    case FrameCache::Source::Shared:
        return "shared";
    case FrameCache::Source::Cached:
        return "hit";
    }
    return "miss";
}

/// The Vot-Space for this request: from memory, else from the (possibly new) fit job.
std::shared_ptr<const fit::VotSpace> spaceFor(Server::Impl& s, const std::shared_ptr<const Dataset>& dataset,
                                              const FitKey& key, const std::string& client) {
    if (auto space = s.cache.findInMemory(key)) return space;
    const auto job = s.fitJobs.submit(dataset, key, client);
    const JobSnapshot done = job->waitFinished(FIT_WAIT);
    if (done.state == JobState::Failed) throw HttpError(500, "fit failed: " + done.error);
    if (done.state != JobState::Done)
        throw HttpError(503, "fit still running; try again later (job " + std::to_string(done.id) + ")");
    return job->space();
}

} // namespace

void installRenderRoute(Server::Impl& s) {
    s.http.Get("/render", [&s](const httplib::Request& req, httplib::Response& res) {
        // Held until the answer is made: one client cannot fill the render queue for everyone.
        const ClientQuota::Ticket place = s.renders.enter(req.remote_addr);
        RenderJob job;
        const auto question = req.target.find('?');
        const std::string_view query = question == std::string::npos
                                           ? std::string_view()
                                           : std::string_view(req.target).substr(question + 1);
        job.params = parseRenderParams(parseQueryString(query));
        const auto dataset = s.registry.find(job.params.dataset);
        refuseWhatVotsCannotDraw(*dataset, job.params); // 409 before any work
        job.volume = dataset->volume;
        // A .vots dataset's window comes from the Vots' own range, as in `vots render FILE.vots`.
        if (dataset->kind == DatasetKind::Volume) job.valueRange = dataset->range;
        // Checked before a possibly long fit: without a context the answer is 503 either way.
        if (!s.renderQueue || !s.renderQueue->hasContext())
            throw HttpError(503, s.renderQueue ? "rendering is unavailable: " + s.renderQueue->contextError()
                                               : "rendering is disabled");
        std::string drawnFrom; // the fit key, or for reference frames the volume
        if (dataset->kind == DatasetKind::Vots) {
            job.space = dataset->space;
            drawnFrom = dataset->name + "_vots"; // the file's one Vot-Space, loaded once
        } else if (job.params.renderer == render::RendererKind::Grid) {
            drawnFrom = dataset->name + "_v" + std::to_string(dataset->contentCrc);
        } else {
            const FitKey key = fitKeyFor(*dataset, job.params.eps, job.params.degree);
            job.space = spaceFor(s, dataset, key, req.remote_addr);
            drawnFrom = key.text();
        }

        FrameCache::Source source = FrameCache::Source::Rendered;
        const auto frame = s.frames.get(
            frameKeyFor(drawnFrom, job.params),
            [&] {
                const RenderResult result = s.renderQueue->submit(job).get(); // throws HttpError (409, ...)
                // PNG encoding runs here, on the HTTP thread, in parallel with the next frame.
                const std::vector<std::uint8_t> png = render::encodePng(result.image);
                return FrameCache::Frame{std::string(png.begin(), png.end()), result.votCount,
                                         result.frameMs};
            },
            &source);
        res.status = 200;
        res.set_header("X-Vots-Vot-Count", std::to_string(frame->votCount));
        res.set_header("X-Vots-Frame-Ms", formatMs(frame->frameMs));
        res.set_header("X-Vots-Frame-Cache", sourceName(source));
        res.set_header("X-Vots-Fit-Seconds", formatMs(job.space ? fitSecondsOf(*job.space) : 0.0));
        res.set_header("Cache-Control", "no-cache");
        res.set_content(frame->png, "image/png");
    });
}

} // namespace vots::server
