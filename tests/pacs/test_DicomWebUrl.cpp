// dicomweb+http(s):// URLs and --dicomweb-auth files: what is accepted, and that secrets stay out of errors.
#include "TempDir.h"

#include "vots/fit/Error.h"
#include "vots/pacs/DicomWebAuth.h"
#include "vots/pacs/DicomWebUrl.h"

#include <gtest/gtest.h>

#include <fstream>

namespace {

using namespace vots::pacs;

TEST(DicomWebUrl, ParsesASeriesUrl) {
    const DicomWebSeries s =
        parseDicomWebSeriesUrl("dicomweb+http://127.0.0.1:8042/dicom-web/studies/1.2.3/series/1.2.3.4");
    EXPECT_FALSE(s.endpoint.https);
    EXPECT_EQ(s.endpoint.host, "127.0.0.1");
    EXPECT_EQ(s.endpoint.port, 8042);
    EXPECT_EQ(s.endpoint.root, "/dicom-web");
    EXPECT_EQ(s.studyUid, "1.2.3");
    EXPECT_EQ(s.seriesUid, "1.2.3.4");
    EXPECT_EQ(s.describe(), "dicomweb+http://127.0.0.1:8042/dicom-web/studies/1.2.3/series/1.2.3.4");
}

TEST(DicomWebUrl, ParsesEndpointsWithDefaultPortsAndRoots) {
    const DicomWebEndpoint https = parseDicomWebEndpoint("dicomweb+https://pacs.example.org/wado/rs/");
    EXPECT_TRUE(https.https);
    EXPECT_EQ(https.port, 443);
    EXPECT_EQ(https.root, "/wado/rs");
    const DicomWebEndpoint bare = parseDicomWebEndpoint("DICOMweb+HTTP://[::1]:8080");
    EXPECT_EQ(bare.host, "::1");
    EXPECT_EQ(bare.port, 8080);
    EXPECT_EQ(bare.root, "");
    EXPECT_EQ(bare.describe(), "dicomweb+http://[::1]:8080");
    const DicomWebSeries atRoot = parseDicomWebSeriesUrl("dicomweb+http://h:1/studies/1.2/series/3.4");
    EXPECT_EQ(atRoot.endpoint.root, "");
}

TEST(DicomWebUrl, RefusesMalformedUrls) {
    for (const char* url :
         {"http://h:1/studies/1/series/2", "dicomweb+http://:80/studies/1/series/2",
          "dicomweb+http://h:0/studies/1/series/2", "dicomweb+http://h:99999/studies/1/series/2",
          "dicomweb+http://h:1/dicom-web", "dicomweb+http://h:1/studies/1.2/series/",
          "dicomweb+http://h:1/studies/1.2/series/3.x", "dicomweb+http://h:1/studies/1/series/2?x=1",
          "dicomweb+http://h%20x:1/studies/1/series/2"})
        EXPECT_THROW(parseDicomWebSeriesUrl(url), vots::fit::InputError) << url;
}

TEST(DicomWebUrl, RefusesCredentialsWithoutRepeatingThem) {
    try {
        parseDicomWebSeriesUrl("dicomweb+http://alice:s3cret-pw@h:1/studies/1/series/2");
        FAIL() << "credentials in a URL were accepted";
    } catch (const vots::fit::InputError& e) {
        EXPECT_EQ(std::string(e.what()).find("s3cret-pw"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("--dicomweb-auth"), std::string::npos) << e.what();
    }
}

std::string writeFile(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

TEST(DicomWebAuth, ReadsBasicAndBearerLines) {
    vots::test::TempDir dir;
    const DicomWebAuth basic = readDicomWebAuthFile(writeFile(dir.file("basic"), "basic alice:pa:ss word\n"));
    EXPECT_EQ(basic.kind, DicomWebAuth::Kind::Basic);
    EXPECT_EQ(basic.user, "alice");
    EXPECT_EQ(basic.secret, "pa:ss word");
    const DicomWebAuth bearer = readDicomWebAuthFile(writeFile(dir.file("bearer"), "bearer tok.en-123"));
    EXPECT_EQ(bearer.kind, DicomWebAuth::Kind::Bearer);
    EXPECT_EQ(bearer.secret, "tok.en-123");
}

TEST(DicomWebAuth, RefusesMalformedFilesWithoutQuotingThem) {
    vots::test::TempDir dir;
    for (const std::string text : {"basic s3cretpw\n", "token s3cretpw", "bearer s3cret pw",
                                   "basic a:s3cretpw\nmore\n", "basic :s3cretpw"}) {
        try {
            readDicomWebAuthFile(writeFile(dir.file("auth"), text));
            FAIL() << "accepted: " << text;
        } catch (const vots::fit::InputError& e) {
            EXPECT_EQ(std::string(e.what()).find("s3cret"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(readDicomWebAuthFile(dir.file("absent")), vots::fit::InputError);
}

} // namespace
