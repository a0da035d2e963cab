// prepareRender and cachedFrame: one frame key, one fit wait and one way into the render queue for all
// routes.
#include "frames/RenderFrames.h"

#include "HttpError.h"
#include "fits/CacheMeta.h"
#include "fits/EpsLadder.h"
#include "vots/render/CameraText.h"
#include "vots/render/Colormap.h"
#include "vots/render/Png.h"
#include "vots/render/RenderMode.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace vots::server {
namespace {

constexpr auto FIT_WAIT = std::chrono::minutes(10); // a request waits this long for its fit at most

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

/// Whether a viewer's token (one that may not start fits) must be refused this key's fit unless it exists:
/// the default eps is the server's own fit (warm-up and the first view), so every role may wait for it.
bool viewerNeedsAMadeFit(bool mayStartFit, const Dataset& dataset, const FitKey& key) {
    return !mayStartFit && key.eps != dataset.defaultEps;
}

HttpError noFitForAViewer(const FitKey& key) {
    return HttpError(403, "this token is a viewer's: it draws the fits an operator has made, and eps " +
                              exactText(key.eps) + " has none yet (an operator's token starts it)");
}

/// The Vot-Space for this request: from memory, else from the (possibly new) fit job.
std::shared_ptr<const fit::VotSpace> spaceFor(Server::Impl& s, const std::shared_ptr<const Dataset>& dataset,
                                              const FitKey& key, const std::string& client,
                                              bool mayStartFit) {
    if (auto space = s.cache.findInMemory(key)) return space;
    if (viewerNeedsAMadeFit(mayStartFit, *dataset, key)) {
        if (auto space = s.cache.find(key)) return space;
        throw noFitForAViewer(key);
    }
    const auto job = s.fitJobs.submit(dataset, key, client);
    const JobSnapshot done = job->waitFinished(FIT_WAIT);
    if (done.state == JobState::Failed) throw HttpError(500, "fit failed: " + done.error);
    if (done.state != JobState::Done)
        throw HttpError(503, "fit still running; try again later (job " + std::to_string(done.id) + ")");
    if (auto space = job->space()) return space;
    // A finished job holds its result only weakly; newer fits can have pushed it out of memory between
    // the job's end and this wake-up. Its cache file, when written, still has it.
    if (auto space = s.cache.find(key)) return space;
    throw HttpError(503, "the fit finished but newer fits have pushed it out of memory; try again");
}

dist::FitRequest fitRequestFor(const Dataset& dataset, float eps, int degree, fit::FitNorm norm) {
    dist::FitRequest request;
    request.dataset = dataset.name;
    request.volumePath = dataset.path;
    request.frame = dataset.frame;
    request.valueRange = dataset.range;
    request.eps = eps;
    request.degree = degree;
    request.norm = norm;
    return request;
}

/// Under mpirun a fit made through the ranks (FitJobs records it as theirs) stays with them: each keeps its
/// cells' boxes and refits from them.
bool madeOnRanks(const ServerStats& stats, const FitKey& key) {
    const std::vector<FitRecord> fits = stats.fits();
    const std::string text = key.text();
    return std::any_of(fits.begin(), fits.end(),
                       [&](const FitRecord& f) { return f.source == "ranks" && f.key == text; });
}

/// Under mpirun: the frame is drawn on every rank from its cells' own fit, so rank 0 fits nothing whole
/// (what the ranks cannot composite was refused before the dataset was looked up); a .vots dataset from
/// each rank's Vots of the file. The ranks fit a new eps before they draw: a viewer's token draws only the
/// fits made.
PreparedRender prepareOnRanks(const Server::Impl& s, const Dataset& dataset, PreparedRender prepared,
                              bool mayStartFit) {
    const fit::FitNorm norm = s.options.fitNorm;
    RenderJob& job = prepared.job;
    if (dataset.kind == DatasetKind::Vots) {
        dist::DrawRequest request;
        request.fit = fitRequestFor(dataset, dataset.space->eps, dataset.space->degree, norm);
        request.votsFile = true;
        request.frame = job.params;
        job.onRanks = std::move(request);
        job.space = dataset.space; // not drawn here: its meta gives the frame's fit time and Vot count
        prepared.drawnFrom = dataset.name + "_vots|ranks";
        return prepared;
    }
    if (job.params.renderer != render::RendererKind::Grid) {
        const FitKey key = fitKeyFor(dataset, job.params.eps, job.params.degree, norm);
        if (viewerNeedsAMadeFit(mayStartFit, dataset, key) && !madeOnRanks(s.stats, key))
            throw noFitForAViewer(key);
    }
    dist::DrawRequest request;
    request.fit = fitRequestFor(dataset, resolveEps(dataset, job.params.eps), job.params.degree, norm);
    request.frame = job.params;
    job.onRanks = std::move(request);
    prepared.drawnFrom = job.params.renderer == render::RendererKind::Grid
                             ? dataset.name + "_v" + std::to_string(dataset.contentCrc) + "|ranks"
                             : fitKeyFor(dataset, job.params.eps, job.params.degree, norm).text() + "|ranks";
    return prepared;
}

} // namespace

PreparedRender prepareRender(Server::Impl& s, const RenderParams& params, const std::string& client,
                             bool mayStartFit) {
    PreparedRender prepared;
    RenderJob& job = prepared.job;
    job.params = params;
    job.owner = client;
    // Under mpirun what the ranks cannot draw is refused before they read anything of the dataset.
    if (s.options.ranks) {
        const std::string refused = s.options.ranks->refusal(params.dataset, params);
        if (!refused.empty()) throw HttpError(409, refused);
    }
    const auto dataset = s.registry.find(job.params.dataset, job.params.frame);
    refuseWhatVotsCannotDraw(*dataset, job.params); // 409 before any work
    job.volume = dataset->volume;
    // A .vots dataset's window comes from the Vots' own range, as in `vots render FILE.vots`.
    if (dataset->kind == DatasetKind::Volume) job.valueRange = dataset->range;
    // Checked before a possibly long fit: without a context the answer is 503 either way.
    if (!s.renderQueue || !s.renderQueue->hasContext())
        throw HttpError(503, s.renderQueue ? "rendering is unavailable: " + s.renderQueue->contextError()
                                           : "rendering is disabled");
    if (s.options.ranks) return prepareOnRanks(s, *dataset, std::move(prepared), mayStartFit);
    if (dataset->kind == DatasetKind::Vots) {
        job.space = dataset->space;
        prepared.drawnFrom = dataset->name + "_vots"; // the file's one Vot-Space, loaded once
    } else if (job.params.renderer == render::RendererKind::Grid) {
        prepared.drawnFrom = dataset->name + "_v" + std::to_string(dataset->contentCrc);
    } else {
        const FitKey key = fitKeyFor(*dataset, job.params.eps, job.params.degree, s.options.fitNorm);
        job.space = spaceFor(s, dataset, key, client, mayStartFit);
        prepared.drawnFrom = key.text();
        prepared.fitKey = key;
        prepared.dataset = dataset;
    }
    return prepared;
}

PreparedRender preparedDraft(Server::Impl& s, const PreparedRender& prepared) {
    // Density shows the Vots themselves: the rung's would be another picture, not a coarser one.
    if (!prepared.fitKey || prepared.fitKey->focus || !prepared.dataset ||
        prepared.job.params.mode == render::RenderMode::Density)
        return prepared;
    const Dataset& dataset = *prepared.dataset;
    const auto rung =
        draftRung(epsLadder(dataset), prepared.fitKey->eps, dataset.range[1] - dataset.range[0]);
    if (!rung) return prepared;
    FitKey key = *prepared.fitKey;
    key.eps = static_cast<float>(*rung);
    auto space = s.cache.findInMemory(key);
    // Only where the render thread keeps both uploaded: else the still after each drag would upload its
    // Vot-Space again, a wait that the drafts' gain does not pay for.
    if (!space || !s.renderQueue->holdsBoth(space->vots.size(), prepared.job.space->vots.size()))
        return prepared;
    PreparedRender draft = prepared;
    draft.job.space = std::move(space);
    draft.drawnFrom = key.text();
    draft.fitKey = key;
    return draft;
}

void uploadAhead(Server::Impl& s, const Dataset& dataset, std::shared_ptr<const fit::VotSpace> space,
                 bool wait) {
    if (!s.renderQueue || !s.renderQueue->hasContext()) return;
    RenderJob job;
    job.params.dataset = dataset.name;
    job.params.width = job.params.height = 16;
    job.space = std::move(space);
    job.volume = dataset.volume;
    if (dataset.kind == DatasetKind::Volume) job.valueRange = dataset.range;
    if (wait) {
        s.renderQueue->render(std::move(job));
        return;
    }
    try {
        s.renderQueue->post(std::move(job));
    } catch (const HttpError&) {
        // A full queue or a stopping server: the viewer's own frame uploads it.
    }
}

FitOnRanks fitOnRanks(Server::Impl& s, const Dataset& dataset, const FitKey& key,
                      const fit::FitProgress& progress) {
    const dist::RanksFit done =
        s.options.ranks->fit(fitRequestFor(dataset, key.eps, key.degree, key.norm), progress);
    return {static_cast<std::size_t>(done.votCount), done.seconds};
}

std::shared_ptr<const FrameCache::Frame> cachedFrame(Server::Impl& s, const PreparedRender& prepared,
                                                     const RenderParams& params, FrameCache::Source* source) {
    return s.frames.get(
        frameKeyFor(prepared.drawnFrom, params),
        [&] {
            RenderJob job = prepared.job;
            job.params = params;
            const RenderResult result = s.renderQueue->render(std::move(job)); // throws HttpError
            // PNG encoding runs here, on the HTTP thread, in parallel with the next frame.
            const auto encodeStart = std::chrono::steady_clock::now();
            const std::vector<std::uint8_t> png = render::encodePng(result.image);
            const double encodeMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - encodeStart)
                    .count();
            const auto& space = prepared.job.space; // job was moved into the queue
            const double fitSeconds = space ? fitSecondsOf(*space) : result.fitMs / 1000.0;
            return FrameCache::Frame{std::string(png.begin(), png.end()),
                                     result.votCount,
                                     result.frameMs,
                                     fitSeconds,
                                     encodeMs,
                                     result.uploadMs};
        },
        source);
}

} // namespace vots::server
