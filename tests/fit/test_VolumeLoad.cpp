// Volume input: exact round trips of every format we read (NIfTI, MetaImage, NRRD, raw), and the type names.
#include "vots/fit/Error.h"
#include "vots/fit/PatientAxes.h"
#include "vots/fit/VolumeLoad.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

using namespace vots::fit;
using vots::test::encode;
using vots::test::FIXTURE_DIMS;
using vots::test::niftiHeader;
using vots::test::TempDir;

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
