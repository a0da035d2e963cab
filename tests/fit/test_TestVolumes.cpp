// The test volumes (scripts/make-test-volumes) and the Cranium CT load with their measured shape and values.
#include "vots/fit/PatientAxes.h"
#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace {

using namespace vots::fit;

std::string testData(const std::string& name) {
    return std::string(VOTS_TEST_DATA_DIR) + "/" + name;
}

double meanOf(const Volume& volume) {
    double sum = 0.0;
    for (const float v : volume.values)
        sum += v;
    return sum / static_cast<double>(volume.values.size());
}

// Coarse histogram: 16 equal bins from min to max, max in the last bin.
std::vector<long> histogram16(const Volume& volume) {
    const auto [lo, hi] = volume.valueRange();
    std::vector<long> bins(16, 0);
    for (const float v : volume.values) {
        const int bin =
            static_cast<int>((static_cast<double>(v) - lo) / (static_cast<double>(hi) - lo) * 16.0);
        ++bins[static_cast<std::size_t>(std::min(bin, 15))];
    }
    return bins;
}

struct TestVolume {
    const char* file;
    std::array<int, 3> dims;
    ScalarType type;
    std::array<double, 3> spacing;
    std::array<double, 3> origin;
    float min, max;
    double mean;
    std::vector<long> histogram;
};

// The volumes scripts/make-test-volumes writes, as measured from its files (the generated ones also by
// construction: the blobs' peak is 255, the orbital's density 0 at the nucleus and just under 1 at its
// lobes' grid points).
const std::vector<TestVolume>& testVolumes() {
    static const std::vector<TestVolume> table = {
        {"blobs_64x64x64_uint8.nrrd",
         {64, 64, 64},
         ScalarType::UInt8,
         {1, 1, 1},
         {0, 0, 0},
         0,
         255,
         9.5882,
         {221671, 15903, 8424, 4808, 3454, 2275, 1706, 1270, 873, 710, 444, 217, 138, 128, 90, 33}},
        {"orbital_64x64x64_float32.nrrd",
         {64, 64, 64},
         ScalarType::Float32,
         {1, 1, 1},
         {0, 0, 0},
         0.0f,
         0.9966160655021667f,
         0.12602,
         {123240, 43520, 36824, 29968, 5312, 4112, 3432, 3016, 2528, 2184, 1904, 1800, 1624, 1248, 912, 520}},
        {"mri-brain_33x41x25_int16.nii",
         {33, 41, 25},
         ScalarType::Int16,
         {2, 2, 2},
         {-32, 40, -16}, // the qform's offset (32, -40, -16) in RAS, in LPS
         -610,
         30393,
         8401.0667,
         {388, 939, 2714, 5336, 8445, 11996, 3812, 163, 8, 5, 3, 3, 3, 4, 2, 4}},
        {"cranium-quarter_64x64x108_int16.nrrd",
         {64, 64, 108},
         ScalarType::Int16,
         {3.8281248, 3.8281248, 1.5},
         {0, 0, 0},
         -1024,
         2621,
         -585.9243,
         {265623, 22382, 6159, 7493, 104989, 9392, 6577, 7558, 7494, 3692, 886, 78, 27, 9, 7, 2}},
    };
    return table;
}

TEST(TestVolumes, EachMatchesItsMeasuredShapeAndValues) {
    for (const TestVolume& row : testVolumes()) {
        SCOPED_TRACE(row.file);
        const Volume volume = loadVolume(testData(row.file));
        EXPECT_EQ(volume.dims, row.dims);
        EXPECT_EQ(volume.sourceType, row.type);
        for (int a = 0; a < 3; ++a) {
            EXPECT_DOUBLE_EQ(volume.spacing[a], row.spacing[a]);
            EXPECT_NEAR(volume.origin[a], row.origin[a], 1e-9);
        }
        EXPECT_EQ(volume.name, std::filesystem::path(row.file).stem().string());
        ASSERT_EQ(volume.values.size(), volume.sampleCount());
        const auto [lo, hi] = volume.valueRange();
        EXPECT_EQ(lo, row.min);
        EXPECT_EQ(hi, row.max);
        EXPECT_NEAR(meanOf(volume), row.mean, 1e-4);
        EXPECT_EQ(histogram16(volume), row.histogram);
    }
}

TEST(TestVolumes, TheBlobsPeakOnceAtTheFirstCentre) {
    const Volume blobs = loadVolume(testData("blobs_64x64x64_uint8.nrrd"));
    EXPECT_EQ(blobs.at(40, 24, 32), 255.f);
    EXPECT_EQ(std::count(blobs.values.begin(), blobs.values.end(), 255.f), 1);
    EXPECT_EQ(blobs.at(0, 0, 0), 0.f);
}

TEST(TestVolumes, NrrdLoaderAndDispatchAgree) {
    const Volume direct = loadNrrd(testData("cranium-quarter_64x64x108_int16.nrrd"));
    const Volume dispatched = loadVolume(testData("cranium-quarter_64x64x108_int16.nrrd"));
    EXPECT_EQ(direct.values, dispatched.values);
    // x runs fastest: the sample at (x, y, z) is values[x + 64 * (y + 64 * z)].
    EXPECT_EQ(direct.at(10, 20, 30), direct.values[10 + 64 * (20 + 64 * 30)]);
}

TEST(TestVolumes, ContentCrcChangesWithAnySampleOrTheGrid) {
    const Volume a = loadVolume(testData("cranium-quarter_64x64x108_int16.nrrd"));
    Volume b = loadVolume(testData("cranium-quarter_64x64x108_int16.nrrd"));
    EXPECT_EQ(a.contentCrc(), b.contentCrc()); // loading twice gives the same fingerprint
    b.values[12345] += 1.f;
    EXPECT_NE(a.contentCrc(), b.contentCrc());
    b.values[12345] -= 1.f;
    b.spacing[2] *= 2.0; // same samples on another grid: a cached fit would be drawn wrongly
    EXPECT_NE(a.contentCrc(), b.contentCrc());
}

TEST(CraniumCt, FetchedHeaderLoadsTheCt) {
    const Volume volume = loadVolume(VOTS_CRANIUM_HEADER); // scripts/fetch-ct writes it
    // The grid runs to the patient's left, anterior and superior (scripts/fetch-ct says why).
    ASSERT_TRUE(volume.orientationKnown);
    EXPECT_EQ(patientDirectionName(volume.patientAxes[0]), "L");
    EXPECT_EQ(patientDirectionName(volume.patientAxes[1]), "A");
    EXPECT_EQ(patientDirectionName(volume.patientAxes[2]), "S");
    EXPECT_EQ(volume.dims, (std::array<int, 3>{256, 256, 108}));
    EXPECT_EQ(volume.sourceType, ScalarType::Int16);
    EXPECT_NEAR(volume.spacing[0], 0.9570312, 1e-9);
    EXPECT_NEAR(volume.spacing[1], 0.9570312, 1e-9);
    EXPECT_DOUBLE_EQ(volume.spacing[2], 1.5);
    const auto [lo, hi] = volume.valueRange();
    EXPECT_EQ(lo, -1024.0f);
    EXPECT_EQ(hi, 2986.0f);
    EXPECT_NEAR(meanOf(volume), -585.96, 0.006);
    EXPECT_EQ(volume.name, "cranium");
}

} // namespace
