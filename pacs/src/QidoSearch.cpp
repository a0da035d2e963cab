// QIDO-RS study and series searches, their query strings and the answers' DICOM JSON read into summaries.
#include "vots/pacs/QidoSearch.h"

#include "DicomJson.h"
#include "DicomWebConnection.h"

#include "vots/fit/Error.h"

#include <httplib.h>

#include <algorithm>

namespace vots::pacs {
namespace {

/// A study date as QIDO-RS takes it (YYYYMMDD) from YYYYMMDD or YYYY-MM-DD (what a date input gives);
/// empty stays empty (no bound).
std::string qidoDate(const std::string& text) {
    std::string date = text;
    if (date.size() == 10 && date[4] == '-' && date[7] == '-')
        date = date.substr(0, 4) + date.substr(5, 2) + date.substr(8, 2);
    const bool digits = std::all_of(date.begin(), date.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (!date.empty() && (date.size() != 8 || !digits))
        throw PacsError(PacsFailure::BadRequest,
                        "study date '" + text.substr(0, 40) + "' is not YYYYMMDD or YYYY-MM-DD");
    return date;
}

void addParameter(std::string& query, const std::string& key, const std::string& value) {
    if (value.empty()) return;
    query += (query.empty() ? "?" : "&") + key + "=" + httplib::detail::encode_query_param(value);
}

int countOf(const nlohmann::json& dataset, const char* tag) {
    return static_cast<int>(dicomNumber(dataset, tag).value_or(0.0));
}

/// GETs the search `path` and reads each dataset of the list it answers with `read`, keeping the summaries
/// that have a UID (`uidOf`): an entry without one cannot be opened. Malformed unless the answer is a list.
template <class Summary, class Read>
std::vector<Summary> searchList(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                                const std::string& path, const std::string& what, Read read,
                                std::string Summary::*uidOf) {
    DicomWebConnection connection(endpoint, access);
    const nlohmann::json answer = connection.getJson(path, what);
    if (!answer.is_array())
        throw PacsError(PacsFailure::Malformed, connection.name() + ": " + what + " did not answer a list");
    std::vector<Summary> summaries;
    for (const nlohmann::json& d : answer) {
        Summary s = read(d);
        if (!(s.*uidOf).empty()) summaries.push_back(std::move(s));
    }
    return summaries;
}

StudySummary studyOf(const nlohmann::json& d) {
    StudySummary s;
    s.studyUid = dicomString(d, "0020000D");
    s.patientName = dicomString(d, "00100010");
    s.patientId = dicomString(d, "00100020");
    s.studyDate = dicomString(d, "00080020");
    s.studyDescription = dicomString(d, "00081030");
    s.accessionNumber = dicomString(d, "00080050");
    s.modalities = dicomStrings(d, "00080061");
    s.seriesCount = countOf(d, "00201206");
    s.instanceCount = countOf(d, "00201208");
    return s;
}

SeriesSummary seriesOf(const nlohmann::json& d) {
    SeriesSummary s;
    s.seriesUid = dicomString(d, "0020000E");
    s.modality = dicomString(d, "00080060");
    s.description = dicomString(d, "0008103E");
    s.seriesNumber = countOf(d, "00200011");
    s.instanceCount = countOf(d, "00201209");
    return s;
}

} // namespace

std::vector<StudySummary> searchStudies(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                                        const StudyQuery& q) {
    const std::string dateFrom = qidoDate(q.studyDateFrom), dateTo = qidoDate(q.studyDateTo);
    if (q.limit < 1) throw PacsError(PacsFailure::BadRequest, "a study search needs a limit of at least 1");
    std::string query;
    addParameter(query, "PatientName", q.patientName);
    addParameter(query, "PatientID", q.patientId);
    if (!dateFrom.empty() || !dateTo.empty()) addParameter(query, "StudyDate", dateFrom + "-" + dateTo);
    addParameter(query, "ModalitiesInStudy", q.modality);
    addParameter(query, "AccessionNumber", q.accessionNumber);
    addParameter(query, "limit", std::to_string(q.limit));
    for (const char* field : {"00081030", "00201206", "00201208", "00080061"})
        addParameter(query, "includefield", field);

    return searchList(endpoint, access, "/studies" + query, "the study search", studyOf,
                      &StudySummary::studyUid);
}

std::vector<SeriesSummary> searchSeries(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                                        const std::string& studyUid) {
    if (studyUid.empty() || studyUid.size() > 64 ||
        !std::all_of(studyUid.begin(), studyUid.end(),
                     [](char c) { return c == '.' || (c >= '0' && c <= '9'); }))
        throw PacsError(PacsFailure::BadRequest, "the study UID '" + studyUid.substr(0, 80) +
                                                     "' is not a DICOM UID (digits and dots)");
    std::vector<SeriesSummary> series = searchList(
        endpoint, access, "/studies/" + studyUid + "/series?includefield=0008103E&includefield=00201209",
        "the series search", seriesOf, &SeriesSummary::seriesUid);
    std::stable_sort(series.begin(), series.end(), [](const SeriesSummary& a, const SeriesSummary& b) {
        return a.seriesNumber < b.seriesNumber;
    });
    return series;
}

} // namespace vots::pacs
