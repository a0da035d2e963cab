// The derived series writer: files the project's reader loads back with their geometry and values, the tags a
// PACS needs, the storage class per modality, the rescale, and all-or-nothing writes.
#include "DicomTags.h"
#include "TempDir.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/pacs/DerivedSeries.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>

namespace vots::test {
namespace {

constexpr int WIDTH = 8, HEIGHT = 6, IMAGES = 4;
constexpr double SPACING = 0.75, STEP = 2.5;
// Image plane: rows run along patient -x... (an inferior view), columns along -y, normal +z.
const std::array<double, 3> ROW{1, 0, 0}, COLUMN{0, -1, 0}, NORMAL{0, 0, -1};

/// HU-like values that depend on pixel and image, so any misplaced pixel shows.
float valueAt(int x, int y, int k) {
    return static_cast<float>(-1000.0 + 37.0 * x + 101.0 * y + 400.0 * k);
}

fit::DicomIdentity ctIdentity() {
    fit::DicomIdentity id;
    id.patientId = "PAT-42";
    id.patientName = "Doe^Jane";
    id.patientBirthDate = "19700101";
    id.patientSex = "F";
    id.studyInstanceUid = "1.2.826.0.1.3680043.10.1234.77";
    id.studyId = "S1";
    id.studyDate = "20260102";
    id.studyTime = "101010";
    id.accessionNumber = "ACC9";
    id.referringPhysicianName = "House^Greg";
    id.modality = "CT";
    id.frameOfReferenceUid = "1.2.826.0.1.3680043.10.1234.78";
    return id;
}

pacs::DerivedSeries series(std::optional<fit::DicomIdentity> source) {
    pacs::DerivedSeries s;
    s.source = std::move(source);
    s.description = "MIP 10 mm / 2.5 mm axial";
    s.geometry.rowDirection = ROW;
    s.geometry.columnDirection = COLUMN;
    s.geometry.pixelSpacingMm = SPACING;
    s.geometry.sliceThicknessMm = 10.0;
    s.geometry.spacingBetweenSlicesMm = STEP;
    s.window = std::array<double, 2>{40.0, 400.0};
    for (int k = 0; k < IMAGES; ++k) {
        pacs::DerivedImage image;
        image.width = WIDTH;
        image.height = HEIGHT;
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x)
                image.pixels.push_back(valueAt(x, y, k));
        image.pixels[0] = -std::numeric_limits<float>::infinity(); // no value: padding
        image.firstPixelCentre = {10.0, 20.0, 30.0 - STEP * k};
        s.images.push_back(std::move(image));
    }
    return s;
}

std::vector<std::string> pathsIn(const TempDir& dir, const std::string& sub, int count) {
    std::filesystem::create_directories(dir.path() / sub);
    std::vector<std::string> paths;
    for (int k = 0; k < count; ++k)
        paths.push_back(dir.file(sub + "/" + std::to_string(k) + ".dcm"));
    return paths;
}

TEST(DerivedSeries, ReadsBackWithItsGeometryAndValues) {
    TempDir dir;
    pacs::writeDerivedSeries(series(ctIdentity()), pathsIn(dir, "mip", IMAGES));
    const fit::Volume v = fit::loadDicomSeries(dir.file("mip"));
    ASSERT_EQ(v.dims, (std::array<int, 3>{WIDTH, HEIGHT, IMAGES}));
    EXPECT_NEAR(v.spacing[0], SPACING, 1e-6);
    EXPECT_NEAR(v.spacing[1], SPACING, 1e-6);
    EXPECT_NEAR(v.spacing[2], STEP, 1e-6);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(v.patientAxes[0][c], ROW[c], 1e-9);
        EXPECT_NEAR(v.patientAxes[1][c], COLUMN[c], 1e-9);
        EXPECT_NEAR(v.patientAxes[2][c], NORMAL[c], 1e-9);
    }
    EXPECT_NEAR(v.origin[0], 10.0, 1e-6);
    EXPECT_NEAR(v.origin[1], 20.0, 1e-6);
    EXPECT_NEAR(v.origin[2], 30.0, 1e-6);
    // A span of thousands of HU is stored in whole HU (slope 1): within half a unit.
    for (int k = 0; k < IMAGES; ++k)
        for (int y = 0; y < HEIGHT; ++y)
            for (int x = 0; x < WIDTH; ++x)
                if (x + y > 0) {
                    EXPECT_NEAR(v.at(x, y, k), valueAt(x, y, k), 0.5) << x << "," << y << "," << k;
                }
    EXPECT_EQ(v.at(0, 0, 0), pacs::PIXEL_PADDING);
}

TEST(DerivedSeries, JoinsTheSourcesPatientAndStudyInANewSeries) {
    TempDir dir;
    const std::vector<std::string> first = pathsIn(dir, "a", IMAGES), second = pathsIn(dir, "b", IMAGES);
    pacs::writeDerivedSeries(series(ctIdentity()), first);
    pacs::writeDerivedSeries(series(ctIdentity()), second);
    std::set<std::string> sops, seriesUids;
    for (const auto& paths : {first, second})
        for (std::size_t k = 0; k < paths.size(); ++k) {
            const DicomTags t(paths[k]);
            EXPECT_EQ(t.text(0x0010, 0x0020), "PAT-42");
            EXPECT_EQ(t.text(0x0010, 0x0010), "Doe^Jane");
            EXPECT_EQ(t.text(0x0010, 0x0030), "19700101");
            EXPECT_EQ(t.text(0x0010, 0x0040), "F");
            EXPECT_EQ(t.text(0x0020, 0x000d), "1.2.826.0.1.3680043.10.1234.77");
            EXPECT_EQ(t.text(0x0008, 0x0050), "ACC9");
            EXPECT_EQ(t.text(0x0008, 0x0020), "20260102");
            EXPECT_EQ(t.text(0x0020, 0x0052), "1.2.826.0.1.3680043.10.1234.78");
            EXPECT_EQ(t.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.2"); // CT Image Storage
            EXPECT_EQ(t.metaText(0x0002, 0x0002), "1.2.840.10008.5.1.4.1.1.2");
            EXPECT_EQ(t.text(0x0008, 0x0060), "CT");
            EXPECT_EQ(t.text(0x0008, 0x0008), "DERIVED\\SECONDARY");
            EXPECT_EQ(t.text(0x0008, 0x103e), "MIP 10 mm / 2.5 mm axial");
            EXPECT_EQ(t.text(0x0018, 0x0050), "10");
            EXPECT_EQ(t.text(0x0018, 0x0088), "2.5");
            EXPECT_EQ(t.text(0x0020, 0x0013), std::to_string(k + 1));
            EXPECT_EQ(t.text(0x0028, 0x0120), "-32768");
            EXPECT_EQ(t.text(0x0028, 0x1050), "40");
            EXPECT_EQ(t.text(0x0028, 0x1051), "400");
            EXPECT_EQ(t.text(0x0028, 0x1053), "1");
            EXPECT_NE(t.text(0x0020, 0x000e), "");
            sops.insert(t.text(0x0008, 0x0018));
            seriesUids.insert(t.text(0x0020, 0x000e));
        }
    EXPECT_EQ(sops.size(), 2u * IMAGES);
    EXPECT_EQ(seriesUids.size(), 2u);
    EXPECT_EQ(seriesUids.count(ctIdentity().studyInstanceUid), 0u);
}

TEST(DerivedSeries, StorageClassFollowsTheModality) {
    TempDir dir;
    fit::DicomIdentity mr = ctIdentity();
    mr.modality = "MR";
    pacs::writeDerivedSeries(series(mr), pathsIn(dir, "mr", IMAGES));
    const DicomTags mrFile(dir.file("mr/0.dcm"));
    EXPECT_EQ(mrFile.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.4");
    EXPECT_EQ(mrFile.text(0x0008, 0x0060), "MR");
    EXPECT_EQ(mrFile.text(0x0028, 0x1053), "1"); // values still in the source's units
    EXPECT_NEAR(fit::loadDicomSeries(dir.file("mr")).at(3, 2, 1), valueAt(3, 2, 1), 0.5);

    pacs::writeDerivedSeries(series(std::nullopt), pathsIn(dir, "nrrd", IMAGES));
    std::set<std::string> studies;
    for (int k = 0; k < IMAGES; ++k) {
        const DicomTags t(dir.file("nrrd/" + std::to_string(k) + ".dcm"));
        EXPECT_EQ(t.text(0x0008, 0x0016), "1.2.840.10008.5.1.4.1.1.7"); // Secondary Capture
        EXPECT_EQ(t.text(0x0008, 0x0060), "OT");
        EXPECT_EQ(t.text(0x0008, 0x0064), "WSD");
        EXPECT_EQ(t.text(0x0020, 0x0037), "1\\0\\0\\0\\-1\\0");
        studies.insert(t.text(0x0020, 0x000d));
    }
    EXPECT_EQ(studies.size(), 1u); // one new study for the whole series
    EXPECT_EQ(studies.count(""), 0u);
}

TEST(DerivedSeries, NarrowRangesSpreadOverTheStoredValues) {
    const pacs::PixelRescale wide = pacs::chooseRescale(-1024.0, 3000.0);
    EXPECT_EQ(wide.slope, 1.0);
    EXPECT_EQ(wide.intercept, 0.0);
    const pacs::PixelRescale narrow = pacs::chooseRescale(0.0, 1.0);
    EXPECT_NEAR(narrow.slope, 1.0 / 65534.0, 1e-12);
    const pacs::PixelRescale huge = pacs::chooseRescale(-1e6, 1e6);
    EXPECT_NEAR(huge.slope * 32767.0 + huge.intercept, 1e6, huge.slope);
    EXPECT_GT(pacs::chooseRescale(5.0, 5.0).slope, 0.0);

    TempDir dir;
    pacs::DerivedSeries s = series(std::nullopt);
    for (auto& image : s.images)
        for (float& v : image.pixels)
            v = std::isfinite(v) ? v / 10000.0f : v; // a span of under one unit
    pacs::writeDerivedSeries(s, pathsIn(dir, "small", IMAGES));
    const fit::Volume v = fit::loadDicomSeries(dir.file("small"));
    for (int k = 0; k < IMAGES; ++k)
        EXPECT_NEAR(v.at(5, 4, k), valueAt(5, 4, k) / 10000.0f, 1e-5);
}

TEST(DerivedSeries, AFailedWriteLeavesNoFile) {
    TempDir dir;
    std::vector<std::string> paths = pathsIn(dir, "out", IMAGES);
    paths[2] = dir.file("missing/2.dcm");
    EXPECT_THROW(pacs::writeDerivedSeries(series(ctIdentity()), paths), fit::InputError);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path() / "out"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "missing"));
}

TEST(DerivedSeries, AWriterStoppedBeforeFinishLeavesNoFile) {
    TempDir dir;
    const std::vector<std::string> paths = pathsIn(dir, "out", IMAGES);
    pacs::DerivedSeries s = series(ctIdentity());
    const std::vector<pacs::DerivedImage> images = std::move(s.images);
    s.valueRange = std::array<double, 2>{-1024.0, 3071.0};
    {
        pacs::DerivedSeriesWriter writer(s, paths);
        writer.add(images[0]);
        writer.add(images[1]);
        EXPECT_THROW(writer.finish(), std::invalid_argument); // two images short
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path() / "out"));

    pacs::DerivedSeriesWriter writer(s, paths);
    for (const pacs::DerivedImage& image : images)
        writer.add(image);
    EXPECT_FALSE(std::filesystem::exists(paths[0])); // only temporaries before finish()
    writer.finish();
    EXPECT_EQ(fit::loadDicomSeries(dir.file("out")).dims[2], IMAGES);
}

} // namespace
} // namespace vots::test
