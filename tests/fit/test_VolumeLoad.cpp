// Volume input: the test volumes (scripts/make-test-volumes), the Cranium CT, and exact round trips of every
// format we read.
#include "vots/fit/Error.h"
#include "vots/fit/PatientAxes.h"
#include "vots/fit/VolumeLoad.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace {

using namespace vots::fit;
using vots::test::encode;
using vots::test::FIXTURE_DIMS;
using vots::test::niftiHeader;
using vots::test::TempDir;

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

// Asserts every fixture sample arrived exactly, in x-fastest order.
void expectFixtureSamples(const Volume& volume, ScalarType type, double slope = 1.0, double inter = 0.0) {
    ASSERT_EQ(volume.dims, FIXTURE_DIMS);
    ASSERT_EQ(volume.values.size(), static_cast<std::size_t>(vots::test::FIXTURE_SAMPLES));
    EXPECT_EQ(volume.sourceType, type);
    const std::vector<double> expected = vots::test::fixtureValues(type);
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const float stored = static_cast<float>(expected[i]);
        const float want = slope == 1.0 && inter == 0.0 ? stored : static_cast<float>(stored * slope + inter);
        ASSERT_EQ(volume.values[i], want) << "sample " << i << " of " << scalarTypeName(type);
    }
}

const ScalarType ALL_TYPES[] = {ScalarType::UInt8,   ScalarType::Int8,   ScalarType::UInt16,
                                ScalarType::Int16,   ScalarType::UInt32, ScalarType::Int32,
                                ScalarType::Float32, ScalarType::Float64};

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

TEST(NiftiRoundTrip, EveryDatatypeInBothByteOrdersPlainAndGzipped) {
    const std::pair<short, ScalarType> datatypes[] = {{2, ScalarType::UInt8},    {4, ScalarType::Int16},
                                                      {8, ScalarType::Int32},    {16, ScalarType::Float32},
                                                      {64, ScalarType::Float64}, {256, ScalarType::Int8},
                                                      {512, ScalarType::UInt16}, {768, ScalarType::UInt32}};
    TempDir dir;
    for (const auto& [datatype, type] : datatypes) {
        for (const bool bigEndian : {false, true}) {
            vots::test::NiftiSpec spec;
            spec.datatype = datatype;
            spec.bitpix = static_cast<short>(8 * encode({0.0}, type, false).size());
            spec.bigEndian = bigEndian;
            const std::string bytes =
                niftiHeader(spec) + encode(vots::test::fixtureValues(type), type, bigEndian);
            const std::string stem = "t" + std::to_string(datatype) + (bigEndian ? "be" : "le");
            const std::string plain = dir.write(stem + ".nii", bytes);
            const std::string gz = dir.file(stem + ".nii.gz");
            vots::test::appendGzip(gz, bytes);
            for (const std::string& path : {plain, gz}) {
                SCOPED_TRACE(path);
                const Volume volume = loadVolume(path);
                expectFixtureSamples(volume, type);
                EXPECT_EQ(volume.spacing, (std::array<double, 3>{0.5, 1.25, 3.0}));
                EXPECT_EQ(volume.name, stem);
            }
        }
    }
}

TEST(NiftiRoundTrip, AppliesSlopeAndInterceptAndNegativePixdim) {
    TempDir dir;
    vots::test::NiftiSpec spec;
    spec.sclSlope = 2.5f;
    spec.sclInter = -10.0f;
    spec.pixdim = {-2.0f, 2.0f, 2.0f}; // a flipped axis still has spacing 2
    const auto values = vots::test::fixtureValues(ScalarType::Int16);
    const Volume volume =
        loadNifti(dir.write("s.nii", niftiHeader(spec) + encode(values, ScalarType::Int16, false)));
    expectFixtureSamples(volume, ScalarType::Int16, 2.5, -10.0);
    EXPECT_EQ(volume.spacing, (std::array<double, 3>{2.0, 2.0, 2.0}));
}

TEST(NiftiRoundTrip, OriginFromSformElseQform) {
    TempDir dir;
    const std::string data = encode(vots::test::fixtureValues(ScalarType::Int16), ScalarType::Int16, true);
    vots::test::NiftiSpec spec;
    spec.bigEndian = true;
    spec.qformCode = 1;
    spec.qoffset = {1.0f, 2.0f, 3.0f};
    // The identity quaternion: the grid runs along R, A, S; the origin in LPS has x and y negated.
    const Volume q = loadNifti(dir.write("q.nii", niftiHeader(spec) + data));
    EXPECT_EQ(q.origin, (std::array<double, 3>{-1, -2, 3}));
    EXPECT_TRUE(q.orientationKnown);
    EXPECT_EQ(q.patientAxes, (PatientAxes{{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}));
    spec.sformCode = 1;
    spec.srowOffset = {-90.0f, -126.0f, -72.0f};
    spec.srow = {{{-0.5f, 0, 0}, {0, 1.25f, 0}, {0, 0, 3.0f}}}; // x along L, y along A, z along S
    // The sform wins; its origin in LPS is (90, 126, -72).
    EXPECT_EQ(loadNifti(dir.write("s.nii", niftiHeader(spec) + data)).origin,
              (std::array<double, 3>{90, 126, -72}));
    spec.srow = {}; // a zero sform matrix says nothing: the qform is used instead
    EXPECT_EQ(loadNifti(dir.write("z.nii", niftiHeader(spec) + data)).origin,
              (std::array<double, 3>{-1, -2, 3}));
    spec.qformCode = 0; // ... and with no qform its translation stays the origin, orientation unknown
    const Volume z = loadNifti(dir.write("z0.nii", niftiHeader(spec) + data));
    EXPECT_FALSE(z.orientationKnown);
    EXPECT_EQ(z.origin, (std::array<double, 3>{-90, -126, -72}));
    spec.sformCode = 0;
    spec.qformCode = 0; // NIfTI method 1: no transform, origin 0
    EXPECT_EQ(loadNifti(dir.write("n.nii", niftiHeader(spec) + data)).origin,
              (std::array<double, 3>{0, 0, 0}));
}

TEST(NiftiRoundTrip, FourDimensionalHeaderWithOneVolumeIsThreeD) {
    TempDir dir;
    vots::test::NiftiSpec spec;
    spec.dim[0] = 5;
    const auto values = vots::test::fixtureValues(ScalarType::Int16);
    const Volume volume =
        loadNifti(dir.write("f.nii", niftiHeader(spec) + encode(values, ScalarType::Int16, false)));
    expectFixtureSamples(volume, ScalarType::Int16);
}

TEST(MetaImageRoundTrip, HeaderAndRawPairInASubfolder) {
    TempDir dir;
    std::filesystem::create_directory(dir.path() / "data");
    const auto values = vots::test::fixtureValues(ScalarType::Int16);
    dir.write("data/head.raw", encode(values, ScalarType::Int16, false));
    const std::string header =
        dir.write("data/head.mhd", "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\n"
                                   "ElementSpacing = 0.5 0.75 2\nOffset = -1 2.5 3\n"
                                   "BinaryData = True\nElementByteOrderMSB = False\n"
                                   "ElementType = MET_SHORT\nElementDataFile = head.raw\n");
    const Volume volume = loadVolume(header);
    expectFixtureSamples(volume, ScalarType::Int16);
    EXPECT_EQ(volume.spacing, (std::array<double, 3>{0.5, 0.75, 2.0}));
    EXPECT_EQ(volume.origin, (std::array<double, 3>{-1.0, 2.5, 3.0}));
    EXPECT_EQ(volume.name, "head");
}

TEST(MetaImageRoundTrip, EveryElementTypeLocalBigEndian) {
    const std::pair<const char*, ScalarType> types[] = {
        {"MET_UCHAR", ScalarType::UInt8},   {"MET_CHAR", ScalarType::Int8},
        {"MET_USHORT", ScalarType::UInt16}, {"MET_SHORT", ScalarType::Int16},
        {"MET_UINT", ScalarType::UInt32},   {"MET_INT", ScalarType::Int32},
        {"MET_FLOAT", ScalarType::Float32}, {"MET_DOUBLE", ScalarType::Float64}};
    TempDir dir;
    for (const auto& [name, type] : types) {
        SCOPED_TRACE(name);
        const std::string header = std::string("NDims = 3\nDimSize = 5 4 3\nElementSize = 1 2 3\n"
                                               "BinaryDataByteOrderMSB = True\nElementType = ") +
                                   name + "\nElementDataFile = LOCAL\n";
        const std::string path = dir.write(std::string(name) + ".mha",
                                           header + encode(vots::test::fixtureValues(type), type, true));
        const Volume volume = loadVolume(path);
        expectFixtureSamples(volume, type);
        EXPECT_EQ(volume.spacing, (std::array<double, 3>{1.0, 2.0, 3.0}));
    }
}

TEST(MetaImageRoundTrip, CompressedLocalData) {
    TempDir dir;
    const auto values = vots::test::fixtureValues(ScalarType::UInt16);
    const std::string packed = vots::test::zlibBytes(encode(values, ScalarType::UInt16, false));
    const std::string path =
        dir.write("c.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_USHORT\n"
                           "CompressedData = True\nCompressedDataSize = " +
                               std::to_string(packed.size()) + "\nElementDataFile = LOCAL\n" + packed);
    expectFixtureSamples(loadMetaImage(path), ScalarType::UInt16);
}

TEST(NrrdRoundTrip, EveryTypeSpellingDetachedRaw) {
    const std::pair<const char*, ScalarType> spellings[] = {{"uchar", ScalarType::UInt8},
                                                            {"unsigned char", ScalarType::UInt8},
                                                            {"uint8", ScalarType::UInt8},
                                                            {"uint8_t", ScalarType::UInt8},
                                                            {"signed char", ScalarType::Int8},
                                                            {"int8", ScalarType::Int8},
                                                            {"int8_t", ScalarType::Int8},
                                                            {"short", ScalarType::Int16},
                                                            {"short int", ScalarType::Int16},
                                                            {"signed short", ScalarType::Int16},
                                                            {"signed short int", ScalarType::Int16},
                                                            {"int16", ScalarType::Int16},
                                                            {"int16_t", ScalarType::Int16},
                                                            {"ushort", ScalarType::UInt16},
                                                            {"unsigned short", ScalarType::UInt16},
                                                            {"unsigned short int", ScalarType::UInt16},
                                                            {"uint16", ScalarType::UInt16},
                                                            {"uint16_t", ScalarType::UInt16},
                                                            {"int", ScalarType::Int32},
                                                            {"signed int", ScalarType::Int32},
                                                            {"int32", ScalarType::Int32},
                                                            {"int32_t", ScalarType::Int32},
                                                            {"uint", ScalarType::UInt32},
                                                            {"unsigned int", ScalarType::UInt32},
                                                            {"uint32", ScalarType::UInt32},
                                                            {"uint32_t", ScalarType::UInt32},
                                                            {"float", ScalarType::Float32},
                                                            {"double", ScalarType::Float64}};
    TempDir dir;
    int n = 0;
    for (const auto& [spelling, type] : spellings) {
        SCOPED_TRACE(spelling);
        const bool bigEndian = (n++ % 2) == 1;
        const std::string data = "d" + std::to_string(n) + ".raw";
        dir.write(data, encode(vots::test::fixtureValues(type), type, bigEndian));
        const std::string header =
            dir.write("h" + std::to_string(n) + ".nhdr",
                      vots::test::nrrdHeader(spelling, "raw",
                                             std::string("endian: ") + (bigEndian ? "big" : "little") +
                                                 "\ndata file: " + data + "\n"));
        expectFixtureSamples(loadVolume(header), type);
    }
}

TEST(NrrdRoundTrip, AttachedGzipWithSpaceDirectionsAndOrigin) {
    TempDir dir;
    const std::string path =
        dir.write("a.nrrd", vots::test::nrrdHeader("float", "gzip",
                                                   "endian: big\nspace: left-posterior-superior\n"
                                                   "space directions: (0,0.5,0) (-1.5,0,0) (0,0,2)\n"
                                                   "space origin: (10,-20.5,30)\n\n"));
    vots::test::appendGzip(path,
                           encode(vots::test::fixtureValues(ScalarType::Float32), ScalarType::Float32, true));
    const Volume volume = loadVolume(path);
    expectFixtureSamples(volume, ScalarType::Float32);
    EXPECT_EQ(volume.spacing, (std::array<double, 3>{0.5, 1.5, 2.0}));
    EXPECT_EQ(volume.origin, (std::array<double, 3>{10.0, -20.5, 30.0}));
}

TEST(NrrdRoundTrip, MultiMemberGzipIsOneStream) {
    TempDir dir;
    const std::string data = encode(vots::test::fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    const std::string path =
        dir.write("m.nrrd", vots::test::nrrdHeader("int16", "gzip", "endian: little\n\n"));
    vots::test::appendGzip(path, data.substr(0, 50));
    vots::test::appendGzip(path, data.substr(50));
    expectFixtureSamples(loadNrrd(path), ScalarType::Int16);
}

TEST(NrrdRoundTrip, SkipsAndMultiFileData) {
    TempDir dir;
    const auto values = vots::test::fixtureValues(ScalarType::UInt16);
    const std::string data = encode(values, ScalarType::UInt16, false);
    const std::string slab = data.substr(0, data.size() / 3);
    // line skip + byte skip on one file
    dir.write("skip.raw", "first line\nsecond\nXYZ" + data);
    expectFixtureSamples(
        loadNrrd(dir.write("skip.nhdr", vots::test::nrrdHeader("ushort", "raw",
                                                               "endian: little\nline skip: 2\nbyte skip: 3\n"
                                                               "data file: skip.raw\n"))),
        ScalarType::UInt16);
    // byte skip -1: the data are the last bytes
    dir.write("tail.raw", std::string(17, '?') + data);
    expectFixtureSamples(
        loadNrrd(dir.write("tail.nhdr", vots::test::nrrdHeader("ushort", "raw",
                                                               "endian: little\nbyte skip: -1\n"
                                                               "datafile: tail.raw\n"))),
        ScalarType::UInt16);
    // one file per z slab, by pattern and by LIST
    for (int z = 0; z < 3; ++z)
        dir.write("slab" + std::to_string(z + 1) + ".raw", data.substr(z * slab.size(), slab.size()));
    expectFixtureSamples(
        loadNrrd(dir.write("pattern.nhdr", vots::test::nrrdHeader("ushort", "raw",
                                                                  "endian: little\n"
                                                                  "data file: slab%d.raw 1 3 1 2\n"))),
        ScalarType::UInt16);
    expectFixtureSamples(
        loadNrrd(dir.write("list.nhdr", vots::test::nrrdHeader("ushort", "raw",
                                                               "endian: little\n"
                                                               "data file: LIST 2\nslab1.raw\n"
                                                               "slab2.raw\nslab3.raw\n"))),
        ScalarType::UInt16);
}

TEST(RawRoundTrip, LayoutWithHeaderSkipAndBothByteOrders) {
    TempDir dir;
    for (const ScalarType type : ALL_TYPES) {
        for (const bool bigEndian : {false, true}) {
            SCOPED_TRACE(scalarTypeName(type) + (bigEndian ? " big" : " little"));
            RawLayout layout;
            layout.dims = FIXTURE_DIMS;
            layout.type = type;
            layout.spacing = {0.9, 0.9, 1.5};
            layout.bigEndian = bigEndian;
            layout.headerBytes = 7;
            const std::string path = dir.write(
                "v.dat", std::string(7, 'h') + encode(vots::test::fixtureValues(type), type, bigEndian));
            const Volume volume = loadVolume(path, layout);
            expectFixtureSamples(volume, type);
            EXPECT_EQ(volume.spacing, layout.spacing);
            EXPECT_EQ(volume.name, "v");
        }
    }
}

TEST(ScalarTypes, ParseEverySpellingAndNameRoundTrips) {
    for (const ScalarType type : ALL_TYPES)
        EXPECT_EQ(parseScalarType(scalarTypeName(type)), type);
    EXPECT_EQ(parseScalarType("short"), ScalarType::Int16);
    EXPECT_EQ(parseScalarType("Unsigned  Char"), ScalarType::UInt8);
    EXPECT_EQ(parseScalarType("float"), ScalarType::Float32);
    EXPECT_EQ(parseScalarType("double"), ScalarType::Float64);
    EXPECT_THROW(parseScalarType("int64"), InputError);
    EXPECT_THROW(parseScalarType(""), InputError);
}

TEST(ScalarTypes, EmptyVolumeRangeIsZero) {
    EXPECT_EQ(Volume{}.valueRange(), (std::array<float, 2>{0.0f, 0.0f}));
}

} // namespace
