// The PACS browser: GET /api/pacs (the services), study and series searches (QIDO-RS), and the open of a
// series as a dataset, a job polled at /api/pacs/opens/{id}.
#include "HttpError.h"
#include "ServerImpl.h"
#include "dicomweb/PacsFailure.h"
#include "dicomweb/SearchAccess.h"
#include "routes/HttpJson.h"

#include "vots/pacs/QidoSearch.h"

#include <algorithm>
#include <cctype>

namespace vots::server {
namespace {

constexpr std::size_t MAX_FIELD_CHARS = 64; // DICOM's longest string VRs (PN per component group, LO)
constexpr int MAX_STUDIES = 500;

/// A search field: at most 64 printable characters; the PACS may take * and ? as wildcards.
std::string fieldParam(const httplib::Request& req, const char* name) {
    const std::string value = req.get_param_value(name);
    if (value.size() > MAX_FIELD_CHARS)
        throw HttpError(400,
                        std::string(name) + ": at most " + std::to_string(MAX_FIELD_CHARS) + " characters");
    for (const char c : value)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\')
            throw HttpError(400, std::string(name) + ": control characters and '\\' are not accepted");
    return value;
}

int limitParam(const httplib::Request& req) {
    if (!req.has_param("limit")) return 100;
    const std::string text = req.get_param_value("limit");
    const bool digits = !text.empty() && text.size() <= 4 &&
                        std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
    const int limit = digits ? std::stoi(text) : 0;
    if (limit < 1 || limit > MAX_STUDIES)
        throw HttpError(400, "limit: a whole number from 1 to " + std::to_string(MAX_STUDIES));
    return limit;
}

/// Runs a pacs call, answering its failure with the status pacsFailure gives it.
template <class Call> auto askPacs(Call&& call) {
    try {
        return call();
    } catch (...) {
        throw pacsFailure(std::current_exception());
    }
}

nlohmann::json studyJson(const pacs::StudySummary& s) {
    return {{"studyUid", s.studyUid},
            {"patientName", s.patientName},
            {"patientId", s.patientId},
            {"studyDate", s.studyDate},
            {"description", s.studyDescription},
            {"accessionNumber", s.accessionNumber},
            {"modalities", s.modalities},
            {"seriesCount", s.seriesCount},
            {"instanceCount", s.instanceCount}};
}

nlohmann::json seriesJson(const pacs::SeriesSummary& s) {
    return {{"seriesUid", s.seriesUid},
            {"modality", s.modality},
            {"description", s.description},
            {"seriesNumber", s.seriesNumber},
            {"instanceCount", s.instanceCount}};
}

nlohmann::json openJson(const SeriesOpenSnapshot& o) {
    return {{"id", o.id},
            {"service", o.service},
            {"studyUid", o.studyUid},
            {"seriesUid", o.seriesUid},
            {"state", std::string(fit::nameOf(o.state))},
            {"received", o.received},
            {"total", o.total},
            {"fromCache", o.fromCache},
            {"dataset", o.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.dataset)},
            {"status", o.errorStatus ? nlohmann::json(o.errorStatus) : nlohmann::json(nullptr)},
            {"error", o.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.error)}};
}

std::uint64_t openIdFrom(const httplib::Request& req) {
    try {
        return std::stoull(req.matches[1].str());
    } catch (const std::exception&) { // out of range: no such open
        throw HttpError(404, "unknown series open");
    }
}

} // namespace

void installPacsRoutes(Server::Impl& s) {
    s.http.Get("/api/pacs", [&s](const httplib::Request&, httplib::Response& res) {
        nlohmann::json services = nlohmann::json::array();
        for (const DicomWebService& service : s.options.dicomWebServices)
            services.push_back({{"name", service.name}, {"url", service.endpoint.describe()}});
        sendJson(res, 200, {{"services", services}});
    });

    s.http.Get(R"(/api/pacs/([A-Za-z0-9_-]{1,64})/studies)", [&s](const httplib::Request& req,
                                                                  httplib::Response& res) {
        const DicomWebService& service = s.seriesOpens.service(req.matches[1].str());
        pacs::StudyQuery query;
        query.patientName = fieldParam(req, "patientName");
        query.patientId = fieldParam(req, "patientId");
        query.studyDateFrom = fieldParam(req, "dateFrom"); // its form is searchStudies' to check
        query.studyDateTo = fieldParam(req, "dateTo");
        query.modality = fieldParam(req, "modality");
        query.accessionNumber = fieldParam(req, "accessionNumber");
        query.limit = limitParam(req);
        const auto studies =
            askPacs([&] { return pacs::searchStudies(service.endpoint, searchAccess(service), query); });
        nlohmann::json out = nlohmann::json::array();
        for (const pacs::StudySummary& study : studies)
            out.push_back(studyJson(study));
        sendJson(res, 200, {{"studies", out}});
    });

    s.http.Get(R"(/api/pacs/([A-Za-z0-9_-]{1,64})/studies/([0-9.]{1,64})/series)",
               [&s](const httplib::Request& req, httplib::Response& res) {
                   const DicomWebService& service = s.seriesOpens.service(req.matches[1].str());
                   const std::string study = req.matches[2].str();
                   const auto series = askPacs(
                       [&] { return pacs::searchSeries(service.endpoint, searchAccess(service), study); });
                   nlohmann::json out = nlohmann::json::array();
                   for (const pacs::SeriesSummary& one : series)
                       out.push_back(seriesJson(one));
                   sendJson(res, 200, {{"series", out}});
               });

    s.http.Post(R"(/api/pacs/([A-Za-z0-9_-]{1,64})/studies/([0-9.]{1,64})/series/([0-9.]{1,64})/open)",
                [&s](const httplib::Request& req, httplib::Response& res) {
                    const SeriesOpenSnapshot open =
                        s.seriesOpens.open(req.matches[1].str(), req.matches[2].str(), req.matches[3].str());
                    sendJson(res, 202, openJson(open));
                });

    s.http.Get(R"(/api/pacs/opens/(\d{1,20}))", [&s](const httplib::Request& req, httplib::Response& res) {
        sendJson(res, 200, openJson(s.seriesOpens.snapshot(openIdFrom(req))));
    });

    s.http.Post(R"(/api/pacs/opens/(\d{1,20})/cancel)",
                [&s](const httplib::Request& req, httplib::Response& res) {
                    sendJson(res, 200, openJson(s.seriesOpens.cancel(openIdFrom(req))));
                });
}

} // namespace vots::server
