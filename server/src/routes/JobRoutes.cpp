// POST /api/fit, GET /api/jobs/{id} and its Server-Sent Events stream of progress.
#include "HttpError.h"
#include "ServerImpl.h"
#include "routes/HttpJson.h"

#include "vots/dist/FrameRanks.h"

#include <chrono>

namespace vots::server {
namespace {

constexpr auto SSE_TICK = std::chrono::milliseconds(500); // longest quiet gap; a comment line keeps it alive

std::uint64_t jobIdFrom(const httplib::Request& req) {
    try {
        return std::stoull(req.matches[1].str());
    } catch (const std::exception&) { // out of range: no such job
        throw HttpError(404, "unknown job");
    }
}

std::string sseEvent(const char* name, const nlohmann::json& data) {
    return std::string("event: ") + name + "\ndata: " + data.dump() + "\n\n";
}

} // namespace

nlohmann::json jobJson(const JobSnapshot& job) {
    return {{"id", job.id},
            {"state", std::string(fit::nameOf(job.state))},
            {"progress", job.progress},
            {"stage", job.stage},
            {"votCount", job.votCount},
            {"fitSeconds", job.fitSeconds},
            {"error", job.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.error)},
            {"dataset", job.dataset},
            {"eps", job.eps},
            {"degree", job.degree},
            {"key", job.key}};
}

void installJobRoutes(Server::Impl& s) {
    s.http.Post("/api/fit", [&s](const httplib::Request& req, httplib::Response& res) {
        const FitParams p = parseFitParams(req.body);
        if (const dist::FrameRanks* ranks = s.options.ranks.get()) {
            // Under mpirun the fit is the ranks' (FitJobs::fitOnRanksThrough): their dataset, no focus;
            // refused before the ranks read anything of another.
            const std::string refused = ranks->refusal(p.dataset, render::FrameRequest{});
            if (!refused.empty()) throw HttpError(409, refused);
            if (p.focus) throw HttpError(409, "under mpirun the ranks fit without a focus sphere");
        }
        const auto dataset = s.registry.find(p.dataset, p.frame);
        refuseFitOfVots(*dataset);
        FitKey key = fitKeyFor(*dataset, p.eps, p.degree, s.options.fitNorm);
        key.focus = p.focus;
        // A viewer's id counts per address, so that no other client can withdraw it from its fit.
        const std::string viewer = p.client.empty() ? std::string() : req.remote_addr + " " + p.client;
        const auto job = s.fitJobs.submit(dataset, key, req.remote_addr, viewer);
        nlohmann::json body = jobJson(job->snapshot());
        body["job"] = job->id();
        sendJson(res, 202, body);
    });

    s.http.Get(R"(/api/jobs/(\d{1,20}))", [&s](const httplib::Request& req, httplib::Response& res) {
        sendJson(res, 200, jobJson(s.fitJobs.find(jobIdFrom(req))->snapshot()));
    });

    s.http.Get(R"(/api/jobs/(\d{1,20})/events)", [&s](const httplib::Request& req, httplib::Response& res) {
        const std::shared_ptr<FitJob> job = s.fitJobs.find(jobIdFrom(req));
        res.set_header("Cache-Control", "no-cache");
        auto seen = std::make_shared<std::uint64_t>(~std::uint64_t{0}); // nothing sent yet
        res.set_chunked_content_provider(
            "text/event-stream", [job, seen](std::size_t, httplib::DataSink& sink) {
                // Called again and again while it returns true; each call waits for news at most one tick.
                const JobSnapshot now =
                    *seen == ~std::uint64_t{0} ? job->snapshot() : job->waitChange(*seen, SSE_TICK);
                std::string out;
                if (now.version != *seen) out = sseEvent("progress", jobJson(now));
                *seen = now.version;
                if (now.state == JobState::Done || now.state == JobState::Failed) {
                    out += sseEvent(now.state == JobState::Done ? "done" : "error", jobJson(now));
                    const bool ok = sink.write(out.data(), out.size());
                    sink.done();
                    return ok;
                }
                if (out.empty())
                    out = ": waiting\n\n"; // a comment: lets a closed connection show up as a failed write
                return sink.write(out.data(), out.size());
            });
    });
}

} // namespace vots::server
