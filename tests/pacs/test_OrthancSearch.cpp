// QIDO-RS study and series searches against the real Orthanc of the pacs fixture.
#include "OrthancState.h"

#include "vots/fit/Error.h"
#include "vots/pacs/QidoSearch.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using namespace vots::pacs;
using namespace vots::test;

const StudySummary* findStudy(const std::vector<StudySummary>& studies, const std::string& uid) {
    const auto it = std::find_if(studies.begin(), studies.end(),
                                 [&](const StudySummary& s) { return s.studyUid == uid; });
    return it == studies.end() ? nullptr : &*it;
}

TEST(OrthancSearch, FindsTheUploadedStudiesWithTheirCounts) {
    const std::vector<StudySummary> studies = searchStudies(orthancEndpoint(), orthancAccess(), {});
    EXPECT_GE(studies.size(), 5u); // the store test may add its own
    const StudySummary* cranium = findStudy(studies, std::string(CRANIUM_SERIES) + ".0");
    ASSERT_NE(cranium, nullptr);
    EXPECT_EQ(cranium->seriesCount, 1);
    EXPECT_EQ(cranium->instanceCount, 108);
    EXPECT_EQ(cranium->modalities, std::vector<std::string>{"CT"});
}

TEST(OrthancSearch, FiltersStudiesByModalityAndDate) {
    StudyQuery mr;
    mr.modality = "MR";
    EXPECT_TRUE(searchStudies(orthancEndpoint(), orthancAccess(), mr).empty());
    StudyQuery ct;
    ct.modality = "CT";
    const auto all = searchStudies(orthancEndpoint(), orthancAccess(), ct);
    EXPECT_GE(all.size(), 4u); // the reports' studies are SR
    ASSERT_FALSE(all.empty());
    const std::string date = all.front().studyDate;
    ASSERT_EQ(date.size(), 8u);
    StudyQuery before;
    before.studyDateTo = "19000101";
    EXPECT_TRUE(searchStudies(orthancEndpoint(), orthancAccess(), before).empty());
    StudyQuery around;
    around.studyDateFrom = date;
    around.studyDateTo = date;
    EXPECT_FALSE(searchStudies(orthancEndpoint(), orthancAccess(), around).empty());
    // As a browser's date input gives it: the same search.
    StudyQuery dashed;
    dashed.studyDateFrom = date.substr(0, 4) + "-" + date.substr(4, 2) + "-" + date.substr(6, 2);
    dashed.studyDateTo = dashed.studyDateFrom;
    EXPECT_EQ(searchStudies(orthancEndpoint(), orthancAccess(), dashed).size(),
              searchStudies(orthancEndpoint(), orthancAccess(), around).size());
    StudyQuery limited;
    limited.limit = 1;
    EXPECT_EQ(searchStudies(orthancEndpoint(), orthancAccess(), limited).size(), 1u);
}

TEST(OrthancSearch, FiltersStudiesByPatientAndAccession) {
    StudyQuery phantom;
    phantom.patientName = "Vots*"; // the writer's patient, Vots^Phantom, by a wildcard
    const auto found = searchStudies(orthancEndpoint(), orthancAccess(), phantom);
    ASSERT_GE(found.size(), 3u);
    for (const StudySummary& s : found)
        EXPECT_EQ(s.patientName, "Vots^Phantom");
    StudyQuery nobody;
    nobody.patientName = "Nobody*";
    EXPECT_TRUE(searchStudies(orthancEndpoint(), orthancAccess(), nobody).empty());
    StudyQuery accession;
    accession.accessionNumber = "NO-SUCH-ACCESSION";
    EXPECT_TRUE(searchStudies(orthancEndpoint(), orthancAccess(), accession).empty());
}

TEST(OrthancSearch, ListsTheSeriesOfAStudy) {
    const std::vector<SeriesSummary> series =
        searchSeries(orthancEndpoint(), orthancAccess(), std::string(CRANIUM_SERIES) + ".0");
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].seriesUid, CRANIUM_SERIES);
    EXPECT_EQ(series[0].description, "Cranium");
    EXPECT_EQ(series[0].modality, "CT");
    EXPECT_EQ(series[0].instanceCount, 108);
    EXPECT_TRUE(searchSeries(orthancEndpoint(), orthancAccess(), "1.2.3.999").empty());
}

TEST(OrthancSearch, RefusedCredentialsAreOneLineWithoutThePassword) {
    DicomWebAccess wrong = orthancAccess();
    const std::string password = wrong.auth.secret;
    wrong.auth.secret = "wrong-" + password;
    try {
        searchStudies(orthancEndpoint(), wrong, {});
        FAIL() << "a wrong password was accepted";
    } catch (const vots::fit::InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("401"), std::string::npos) << message;
        EXPECT_EQ(message.find(password), std::string::npos) << message;
    }
    for (const char* notADate : {"2024-1-1", "yesterday", "2024010"}) {
        StudyQuery badDate;
        badDate.studyDateFrom = notADate;
        EXPECT_THROW(searchStudies(orthancEndpoint(), orthancAccess(), badDate), vots::fit::InputError)
            << notADate;
    }
}

} // namespace
