// Searching a DICOMweb service (QIDO-RS): studies by patient, date, modality or accession; a study's series.
#pragma once

#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"

#include <string>
#include <vector>

namespace vots::pacs {

/// Empty fields do not constrain. Names may hold the wildcards * and ?; dates are YYYYMMDD or YYYY-MM-DD.
struct StudyQuery {
    std::string patientName;
    std::string patientId;
    std::string studyDateFrom; // inclusive; only one of the two: an open range
    std::string studyDateTo;   // inclusive
    std::string modality;      // ModalitiesInStudy, e.g. CT
    std::string accessionNumber;
    int limit = 100; // at most this many studies (the service may cap it lower)
};

struct StudySummary {
    std::string studyUid;
    std::string patientName;
    std::string patientId;
    std::string studyDate;
    std::string studyDescription;
    std::string accessionNumber;
    std::vector<std::string> modalities;
    int seriesCount = 0;
    int instanceCount = 0;
};

struct SeriesSummary {
    std::string seriesUid;
    std::string modality;
    std::string description;
    int seriesNumber = 0;
    int instanceCount = 0;
};

/// The studies that match, in the service's order. Throws fit::InputError with one line (refused
/// credentials, unreachable service, a malformed answer, a malformed date).
std::vector<StudySummary> searchStudies(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                                        const StudyQuery& query);

/// The series of a study, sorted by series number. Throws as searchStudies does.
std::vector<SeriesSummary> searchSeries(const DicomWebEndpoint& endpoint, const DicomWebAccess& access,
                                        const std::string& studyUid);

} // namespace vots::pacs
