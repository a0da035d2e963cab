// The WADO-RS and QIDO-RS resource paths of a series, below the service's root, and the shared internals.
#pragma once

#include "vots/pacs/DicomWebUrl.h"
#include "vots/pacs/SeriesRetrieve.h"

#include <string>

namespace vots::pacs {

class DicomWebConnection;

/// The multipart type every retrieve asks for: the stored transfer syntax, so nothing is transcoded.
inline constexpr const char* DICOM_MULTIPART_ACCEPT =
    "multipart/related; type=\"application/dicom\"; transfer-syntax=*";

/// "/studies/STUDY/series/SERIES".
inline std::string seriesResource(const DicomWebSeries& s) {
    return "/studies/" + s.studyUid + "/series/" + s.seriesUid;
}
/// "/studies/STUDY/series?SeriesInstanceUID=SERIES".
inline std::string seriesSearchResource(const DicomWebSeries& s) {
    return "/studies/" + s.studyUid + "/series?SeriesInstanceUID=" + s.seriesUid;
}

/// announceSeries over an open connection.
SeriesAnnouncement announceSeries(DicomWebConnection& connection, const DicomWebSeries& series);

} // namespace vots::pacs
