// What GET /render and GET /turntable share: a request's render job, and its frames through the cache and
// queue.
#pragma once

#include "ServerImpl.h"
#include "frames/FrameCache.h"
#include "frames/RenderQueue.h"

#include <memory>
#include <optional>
#include <string>

namespace vots::server {

/// A request made ready to draw: the dataset found, its Vot-Space fitted (or waited for), and the name
/// of what its frames are drawn from (the fit key, or for grid frames the volume).
struct PreparedRender {
    RenderJob job;
    std::string drawnFrom;
    // Set when the frame is drawn from a fit made here: its key, and the dataset it fits.
    std::optional<FitKey> fitKey;
    std::shared_ptr<const Dataset> dataset;
};

/// Throws HttpError: 404 for an unknown dataset, 409 for what Vots cannot draw, 503 without a renderer
/// or while the fit still runs, 500 when it failed, 403 when the Vots need a fit `mayStartFit` forbids
/// (a viewer's token: only the dataset's default eps and fits already made). `client` is the fit job's
/// owner.
PreparedRender prepareRender(Server::Impl& s, const RenderParams& params, const std::string& client,
                             bool mayStartFit = true);

/// A viewer's draft of `prepared`: drawn from the fit at its eps's draft rung (draftRung) when the fit
/// cache holds that in memory, with `drawnFrom` and `fitKey` its; else `prepared` itself. Never waits for
/// a fit: the warm-ups make the draft rung's first (WarmUpFits). Not for a focus fit, a .vots dataset,
/// the grid renderer or the ranks, which have no such rung, nor for density (the Vots' own sizes).
PreparedRender preparedDraft(Server::Impl& s, const PreparedRender& prepared);

/// Under mpirun: the ranks fit their cells at the key's eps (dist::FrameRanks::fit), which the next
/// frames at that eps find held; this process's fit reports through `progress`. Throws what the port
/// throws (dist::RanksLost, dist::RanksOverBudget, fit::InputError).
FitOnRanks fitOnRanks(Server::Impl& s, const Dataset& dataset, const FitKey& key,
                      const fit::FitProgress& progress);

/// Has the render thread upload `space` (of `dataset`) by drawing a 16x16 frame of it: the upload is what
/// a first frame of a Vot-Space waits on. `wait`: returns once it is drawn (throws what render() throws);
/// else it only queues the frame, and a queue that takes none (full, no renderer) is no error.
void uploadAhead(Server::Impl& s, const Dataset& dataset, std::shared_ptr<const fit::VotSpace> space,
                 bool wait);

/// The PNG of the frame `params` names (the job's data with these parameters), from the frame cache,
/// else drawn on the render queue and kept there. Throws HttpError from the queue (409, 503, ...).
std::shared_ptr<const FrameCache::Frame> cachedFrame(Server::Impl& s, const PreparedRender& prepared,
                                                     const RenderParams& params, FrameCache::Source* source);

} // namespace vots::server
