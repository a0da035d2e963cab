// GET /api/stats: frame times, recent fits with their Vot counts, fit jobs, connections, and what the caches
// hold.
#include "ServerImpl.h"
#include "routes/HttpJson.h"
#include "vots/dist/FrameRanks.h"

namespace vots::server {

void installStatsRoute(Server::Impl& s) {
    s.http.Get("/api/stats", [&s](const httplib::Request&, httplib::Response& res) {
        const FrameSummary frames = s.stats.frames();
        const FrameCache::Summary kept = s.frames.summary();
        nlohmann::json fits = nlohmann::json::array();
        for (const FitRecord& f : s.stats.fits())
            fits.push_back({{"key", f.key},
                            {"dataset", f.dataset},
                            {"eps", f.eps},
                            {"degree", f.degree},
                            {"votCount", f.votCount},
                            {"fitSeconds", f.fitSeconds},
                            {"source", f.source}});
        nlohmann::json memory = nlohmann::json::array();
        std::size_t memoryBytes = 0;
        for (const auto& e : s.cache.memoryEntries()) {
            memory.push_back({{"key", e.key}, {"votCount", e.votCount}, {"bytes", e.bytes}});
            memoryBytes += e.bytes;
        }
        nlohmann::json disk = nlohmann::json::array();
        for (const auto& e : s.cache.diskEntries())
            disk.push_back({{"file", e.file}, {"bytes", e.bytes}});
        nlohmann::json loaded = nlohmann::json::array();
        for (const auto& d : s.registry.loaded())
            loaded.push_back(d->name);
        const HeldFramesSummary held = s.registry.heldFrames();

        const WarmUpSummary warm = s.fitJobs.warmUps();
        const BoxCacheStats boxes = s.fitJobs.boxCaches();
        const RenderQueue* queue = s.renderQueue.get();
        nlohmann::json renderer = {{"available", queue && queue->hasContext()},
                                   {"name", queue ? queue->rendererName() : ""},
                                   {"walkShader", queue ? queue->walkShaderName() : ""},
                                   {"mipStrategy", queue ? queue->mipStrategyName() : ""},
                                   {"error", queue ? queue->contextError() : "renderer disabled"},
                                   {"waiting", queue ? queue->waiting() : 0}};
        // Under mpirun: the ranks and their parts of the last composited frame.
        const dist::FrameRanks* ranks = s.options.ranks.get();
        nlohmann::json rankTimes = nlohmann::json::array();
        if (ranks)
            for (const dist::RankTimes& t : ranks->lastTimes())
                rankTimes.push_back({{"rank", t.rank},
                                     {"fitMs", t.fitMs},
                                     {"frameMs", t.frameMs},
                                     {"compositeMs", t.compositeMs},
                                     {"votCount", t.votCount}});
        sendJson(res, 200,
                 {{"ranks", ranks ? ranks->ranks() : 1},
                  {"rankTimes", rankTimes},
                  {"frames",
                   {{"count", frames.frames},
                    {"lastMs", frames.lastMs},
                    {"medianMs", frames.medianMs},
                    {"superseded", frames.superseded}}},
                  {"frameCache",
                   {{"entries", kept.entries},
                    {"bytes", kept.bytes},
                    {"budgetBytes", kept.budgetBytes},
                    {"rendered", kept.rendered},
                    {"shared", kept.shared},
                    {"cached", kept.cached}}},
                  {"heldFrames",
                   {{"bytes", held.bytes}, {"boundBytes", held.boundBytes}, {"frames", held.frames}}},
                  {"renderer", renderer},
                  {"fits", fits},
                  {"fitJobs", {{"active", s.fitJobs.activeCount()}}},
                  {"connections",
                   {{"waiting", s.http.waitingConnections()},
                    {"eventStreams", s.http.runningStreams()},
                    {"viewerSockets", s.viewers ? s.viewers->openSockets() : 0}}},
                  {"warmUps",
                   {{"started", warm.started},
                    {"finished", warm.finished},
                    {"cancelled", warm.cancelled},
                    {"failed", warm.failed},
                    {"running", warm.running},
                    {"lastKey", warm.lastKey},
                    {"lastEps", warm.lastEps},
                    {"lastSeconds", warm.lastSeconds}}},
                  {"boxCaches",
                   {{"caches", boxes.caches},
                    {"bytes", boxes.bytes},
                    {"budgetBytes", boxes.budgetBytes},
                    {"dropped", boxes.dropped}}},
                  {"cache",
                   {{"memory", memory},
                    {"memoryBytes", memoryBytes},
                    {"disk", disk},
                    {"diskEnabled", s.cache.diskEnabled()},
                    {"dir", s.cache.directory().string()}}},
                  {"datasets", {{"available", s.registry.names().size()}, {"loaded", loaded}}}});
    });
}

} // namespace vots::server
