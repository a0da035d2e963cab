// Runs of z planes: read by offset from every uncompressed format, streamed from gzip NRRD, NIfTI and zlib
// MetaImage, bit-identical to cutting the whole.
#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>

namespace {

using namespace vots::fit;
using vots::test::encode;
using vots::test::FIXTURE_DIMS;
using vots::test::fixtureValues;
using vots::test::TempDir;

// Every byte of the samples and every field of the grid, so "equal" means bit-identical.
void expectSameVolume(const Volume& got, const Volume& want) {
    EXPECT_EQ(got.dims, want.dims);
    EXPECT_EQ(got.spacing, want.spacing);
    EXPECT_EQ(std::memcmp(got.origin.data(), want.origin.data(), sizeof got.origin), 0);
    EXPECT_EQ(got.patientAxes, want.patientAxes);
    EXPECT_EQ(got.orientationKnown, want.orientationKnown);
    EXPECT_EQ(got.sourceType, want.sourceType);
    EXPECT_EQ(got.name, want.name);
    ASSERT_EQ(got.values.size(), want.values.size());
    // memcmp of an empty vector's data() is undefined (it may be null); the grid-only volumes have none.
    if (!got.values.empty()) {
        EXPECT_EQ(std::memcmp(got.values.data(), want.values.data(), got.values.size() * sizeof(float)), 0);
    }
    EXPECT_EQ(got.compact, want.compact);
}

struct Case {
    std::string path;
    std::optional<RawLayout> raw;
};

// Each plane run of the fixture grid, both storages: read by offset (or not) and cut agree.
void expectPlanesMatchCut(const Case& c, bool byOffset) {
    SCOPED_TRACE(c.path);
    EXPECT_EQ(readsOnlyPlanes(c.path, c.raw), byOffset);
    for (const SampleStorage storage : {SampleStorage::Float, SampleStorage::Source}) {
        const Volume whole = loadVolume(c.path, c.raw, storage);
        for (int first = 0; first < FIXTURE_DIMS[2]; ++first) {
            for (int last = first; last < FIXTURE_DIMS[2]; ++last) {
                SCOPED_TRACE("planes " + std::to_string(first) + ".." + std::to_string(last));
                const Volume cut = planesOf(whole, first, last);
                ASSERT_EQ(cut.dims[2], last - first + 1);
                const PlanesOfGrid slab = loadVolumePlanes(c.path, first, last, c.raw, storage);
                expectSameVolume(slab.planes, cut);
                expectSameVolume(slab.whole, gridOf(whole));
                EXPECT_TRUE(slab.whole.values.empty() && !slab.whole.isCompact());
            }
        }
    }
}

const ScalarType TYPES[] = {ScalarType::UInt8, ScalarType::Int16,   ScalarType::UInt16,
                            ScalarType::Int32, ScalarType::Float32, ScalarType::Float64};

std::string nrrdType(ScalarType type) {
    return type == ScalarType::Float32   ? "float"
           : type == ScalarType::Float64 ? "double"
                                         : scalarTypeName(type);
}

TEST(VolumePlanes, CutKeepsPlanesInOrderAndMovesTheOriginAlongTheZAxis) {
    Volume volume;
    volume.dims = {2, 2, 4};
    volume.spacing = {1.0, 1.0, 2.5};
    volume.origin = {10.0, 20.0, 30.0};
    volume.patientAxes = {{{1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0}}};
    volume.orientationKnown = true;
    for (int i = 0; i < 16; ++i)
        volume.values.push_back(static_cast<float>(i));
    const Volume part = planesOf(volume, 1, 2);
    EXPECT_EQ(part.dims, (std::array<int, 3>{2, 2, 2}));
    EXPECT_EQ(part.values, (std::vector<float>{4, 5, 6, 7, 8, 9, 10, 11}));
    EXPECT_EQ(part.origin, (std::array<double, 3>{10.0, 17.5, 30.0})); // one plane down -y
    EXPECT_EQ(part.patientAxes, volume.patientAxes);
    EXPECT_THROW(planesOf(volume, 2, 4), InputError);
    EXPECT_THROW(planesOf(volume, -1, 0), InputError);
    EXPECT_THROW(planesOf(volume, 2, 1), InputError);
}

TEST(VolumePlanes, NrrdAttachedAndDetachedRawEveryType) {
    TempDir dir;
    for (const ScalarType type : TYPES) {
        for (const bool bigEndian : {false, true}) {
            const std::string data = encode(fixtureValues(type), type, bigEndian);
            const std::string stem = nrrdType(type) + (bigEndian ? "be" : "le");
            const std::string fields = std::string("endian: ") + (bigEndian ? "big" : "little") +
                                       "\nspace: RAS\nspace directions: (0,1.5,0) (-2,0,0) (0,0,3)\n"
                                       "space origin: (1,2,3)\n";
            const std::string attached = dir.write(
                stem + ".nrrd", vots::test::nrrdHeader(nrrdType(type), "raw", fields) + "\n" + data);
            dir.write(stem + ".raw", "skip me\n" + data);
            const std::string detached =
                dir.write(stem + ".nhdr",
                          vots::test::nrrdHeader(nrrdType(type), "raw",
                                                 fields + "line skip: 1\ndata file: " + stem + ".raw\n"));
            expectPlanesMatchCut({attached, std::nullopt}, true);
            expectPlanesMatchCut({detached, std::nullopt}, true);
        }
    }
}

TEST(VolumePlanes, NrrdDataFilesSplitOtherThanByPlane) {
    // Four files of 15 samples each: plane runs start and end inside files.
    TempDir dir;
    const std::string data = encode(fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    std::string list;
    for (int k = 0; k < 4; ++k) {
        dir.write("part" + std::to_string(k) + ".raw", data.substr(k * data.size() / 4, data.size() / 4));
        list += "part" + std::to_string(k) + ".raw\n";
    }
    const std::string header = dir.write(
        "list.nhdr", vots::test::nrrdHeader("short", "raw", "endian: little\ndata file: LIST\n" + list));
    expectPlanesMatchCut({header, std::nullopt}, true);
}

TEST(VolumePlanes, NiftiPlainEveryTypeAndScaled) {
    TempDir dir;
    const std::pair<short, ScalarType> datatypes[] = {{2, ScalarType::UInt8},    {4, ScalarType::Int16},
                                                      {16, ScalarType::Float32}, {64, ScalarType::Float64},
                                                      {512, ScalarType::UInt16}, {8, ScalarType::Int32}};
    for (const auto& [datatype, type] : datatypes) {
        for (const float slope : {0.0f, 2.5f}) {
            if (slope != 0.0f && type == ScalarType::Float64) continue; // its 3e38 would leave float range
            vots::test::NiftiSpec spec;
            spec.datatype = datatype;
            spec.bitpix = static_cast<short>(8 * encode({0.0}, type, false).size());
            spec.sclSlope = slope;
            spec.sclInter = slope != 0.0f ? -10.0f : 0.0f;
            spec.sformCode = 1;
            spec.srow = {{{-0.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 3.0f}, {0.0f, 1.25f, 0.0f}}};
            spec.srowOffset = {4.0f, -5.0f, 6.0f};
            const std::string path =
                dir.write(std::to_string(datatype) + "s" + std::to_string(static_cast<int>(slope)) + ".nii",
                          vots::test::niftiHeader(spec) + encode(fixtureValues(type), type, false));
            expectPlanesMatchCut({path, std::nullopt}, true);
            // The same file gzipped whole (.nii.gz): its planes are streamed, scaled alike.
            const std::string gz = dir.file(std::to_string(datatype) + "s" +
                                            std::to_string(static_cast<int>(slope)) + ".nii.gz");
            vots::test::appendGzip(gz,
                                   vots::test::niftiHeader(spec) + encode(fixtureValues(type), type, false));
            expectPlanesMatchCut({gz, std::nullopt}, true);
        }
    }
}

TEST(VolumePlanes, MetaImageLocalAndDetachedWithHeaderSize) {
    TempDir dir;
    for (const ScalarType type : {ScalarType::Int16, ScalarType::Float32}) {
        const char* met = type == ScalarType::Int16 ? "MET_SHORT" : "MET_FLOAT";
        const std::string data = encode(fixtureValues(type), type, true);
        const std::string fields = std::string("NDims = 3\nDimSize = 5 4 3\nElementSpacing = 1 2 3\n"
                                               "Offset = 1 2 3\nTransformMatrix = 0 1 0 1 0 0 0 0 -1\n"
                                               "ElementByteOrderMSB = True\nElementType = ") +
                                   met + "\n";
        const std::string local =
            dir.write(std::string(met) + ".mha", fields + "ElementDataFile = LOCAL\n" + data);
        dir.write(std::string(met) + ".raw", std::string(11, 'h') + data);
        const std::string detached = dir.write(
            std::string(met) + ".mhd", fields + "HeaderSize = 11\n" + "ElementDataFile = " + met + ".raw\n");
        expectPlanesMatchCut({local, std::nullopt}, true);
        expectPlanesMatchCut({detached, std::nullopt}, true);
    }
}

TEST(VolumePlanes, RawLayoutWithHeaderBytes) {
    TempDir dir;
    for (const ScalarType type : TYPES) {
        RawLayout layout;
        layout.dims = FIXTURE_DIMS;
        layout.type = type;
        layout.spacing = {0.5, 0.5, 2.0};
        layout.bigEndian = true;
        layout.headerBytes = 9;
        const std::string path = dir.write(scalarTypeName(type) + ".dat",
                                           std::string(9, 'h') + encode(fixtureValues(type), type, true));
        expectPlanesMatchCut({path, layout}, true);
    }
}

TEST(VolumePlanes, GzipAndZlibPlanesAreStreamed) {
    TempDir dir;
    const std::string data = encode(fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    const std::string gzNrrd =
        dir.write("g.nrrd", vots::test::nrrdHeader("short", "gzip", "endian: little\n") + "\n");
    vots::test::appendGzip(gzNrrd, data);
    vots::test::NiftiSpec spec;
    const std::string gzNifti = dir.file("g.nii.gz");
    vots::test::appendGzip(gzNifti, vots::test::niftiHeader(spec) + data);
    const std::string packed = vots::test::zlibBytes(data);
    const std::string zlibMha = dir.write("z.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
                                                   "CompressedData = True\nElementDataFile = LOCAL\n" +
                                                       packed);
    expectPlanesMatchCut({gzNrrd, std::nullopt}, true);
    expectPlanesMatchCut({gzNifti, std::nullopt}, true);
    expectPlanesMatchCut({zlibMha, std::nullopt}, true);
    // A detached zlib payload with HeaderSize before it and CompressedDataSize short of the file's end:
    // the stream is read over its stated bytes only, whatever follows them.
    dir.write("z.zraw", "HEADER" + packed + "trailing bytes, not zlib");
    const std::string zlibMhd =
        dir.write("z.mhd", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\nCompressedData = True\n"
                           "HeaderSize = 6\nCompressedDataSize = " +
                               std::to_string(packed.size()) + "\nElementDataFile = z.zraw\n");
    expectPlanesMatchCut({zlibMhd, std::nullopt}, true);
    // A stream cut short is refused by whoever reads its end.
    const std::string cutMha = dir.write("c.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
                                                  "CompressedData = True\nElementDataFile = LOCAL\n" +
                                                      packed.substr(0, packed.size() - 8));
    EXPECT_THROW(loadVolumePlanes(cutMha, 2, 2, std::nullopt, SampleStorage::Float), InputError);
    EXPECT_THROW(loadVolume(cutMha), InputError);
}

TEST(VolumePlanes, GzipNrrdDataFilesMembersAndSkips) {
    TempDir dir;
    for (const ScalarType type : TYPES) {
        SCOPED_TRACE(nrrdType(type));
        const std::string data = encode(fixtureValues(type), type, true);
        // Four data files of 15 samples each (runs of planes start and end inside files), each after a
        // skipped line and 3 decompressed bytes of byte skip; the second file as two gzip members.
        const std::size_t quarter = data.size() / 4;
        std::string list;
        for (std::size_t k = 0; k < 4; ++k) {
            const std::string name = "p" + nrrdType(type) + std::to_string(k) + ".gz";
            const std::string share = "xyz" + data.substr(k * quarter, quarter);
            dir.write(name, "line to skip\n");
            if (k == 1) {
                vots::test::appendGzip(dir.file(name), share.substr(0, 7));
                vots::test::appendGzip(dir.file(name), share.substr(7));
            } else {
                vots::test::appendGzip(dir.file(name), share);
            }
            list += name + "\n";
        }
        const std::string header = dir.write(
            nrrdType(type) + ".nhdr",
            vots::test::nrrdHeader(nrrdType(type), "gzip",
                                   "endian: big\nline skip: 1\nbyte skip: 3\ndata file: LIST\n" + list));
        expectPlanesMatchCut({header, std::nullopt}, true);
    }
}

namespace {

// A gzip NRRD of `planes` planes of 192 x 160 int16 samples that compress poorly (so the stream is
// longer than the reader's chunks of input), written as one gzip member per 7 planes.
std::string writeLargeGzipNrrd(TempDir& dir, const std::string& name, int planes) {
    const int nx = 192, ny = 160;
    std::vector<double> values(static_cast<std::size_t>(nx) * ny * planes);
    std::uint32_t state = 12345;
    for (double& v : values) {
        state = state * 1664525u + 1013904223u;
        v = static_cast<double>(static_cast<std::int16_t>(state >> 16));
    }
    const std::string data = encode(values, ScalarType::Int16, false);
    const std::string path =
        dir.write(name, "NRRD0004\ntype: short\ndimension: 3\nsizes: 192 160 " + std::to_string(planes) +
                            "\nencoding: gzip\nendian: little\n\n");
    const std::size_t planeBytes = std::size_t{nx} * ny * 2;
    for (int z = 0; z < planes; z += 7)
        vots::test::appendGzip(path, data.substr(z * planeBytes, 7 * planeBytes));
    return path;
}

} // namespace

TEST(VolumePlanes, LargeGzipNrrdPlanesAreTheCutOfTheWholeAndHoldOnlyThePlanes) {
    TempDir dir;
    const int planes = 40;
    const std::string path = writeLargeGzipNrrd(dir, "large.nrrd", planes);
    ASSERT_GT(std::filesystem::file_size(path), std::uintmax_t{2} << 20); // more than 2 chunks of input
    const std::size_t plane = 192 * 160;
    for (const SampleStorage storage : {SampleStorage::Float, SampleStorage::Source}) {
        const Volume whole = loadVolume(path, std::nullopt, storage);
        for (const auto& [first, last] : {std::pair{0, 0}, {0, 13}, {6, 7}, {13, 26}, {20, 39}, {39, 39}}) {
            SCOPED_TRACE("planes " + std::to_string(first) + ".." + std::to_string(last));
            const PlanesOfGrid slab = loadVolumePlanes(path, first, last, std::nullopt, storage);
            expectSameVolume(slab.planes, planesOf(whole, first, last));
            // The reader gives back the slab alone, never the whole volume.
            EXPECT_EQ(slab.planes.heldSamples(), plane * static_cast<std::size_t>(last - first + 1));
            EXPECT_TRUE(slab.whole.values.empty() && !slab.whole.isCompact());
        }
    }
}

TEST(VolumePlanes, GzipPlanesStopAfterTheirLastPlaneAndTheEndIsCheckedByItsReader) {
    // The stream cut short at 60 %: the whole load refuses it, the first planes never reach the cut, and
    // the reader of the last planes refuses it as the whole load does.
    TempDir dir;
    const std::string path = writeLargeGzipNrrd(dir, "cut.nrrd", 40);
    std::filesystem::resize_file(path, std::filesystem::file_size(path) * 6 / 10);
    EXPECT_THROW(loadVolume(path), InputError);
    EXPECT_EQ(loadVolumePlanes(path, 0, 10).planes.dims, (std::array<int, 3>{192, 160, 11}));
    EXPECT_THROW(loadVolumePlanes(path, 30, 39), InputError);
    // Bytes after the stream: only the reader of the stream's end sees them.
    const std::string longer = writeLargeGzipNrrd(dir, "longer.nrrd", 14);
    std::ofstream(longer, std::ios::binary | std::ios::app) << "trailing";
    EXPECT_THROW(loadVolume(longer), InputError);
    EXPECT_NO_THROW(loadVolumePlanes(longer, 0, 12));
    EXPECT_THROW(loadVolumePlanes(longer, 12, 13), InputError);
}

TEST(VolumePlanes, ReadsOnlyThePlanesBytes) {
    // A NaN (no data) in plane 2: the whole load holds it, planes 0..1 never read it.
    TempDir dir;
    std::vector<double> values = fixtureValues(ScalarType::Float32);
    values.back() = std::numeric_limits<double>::quiet_NaN();
    const std::string path =
        dir.write("nan.nrrd", vots::test::nrrdHeader("float", "raw", "endian: little\n") + "\n" +
                                  encode(values, ScalarType::Float32, false));
    EXPECT_EQ(loadVolume(path).nonFiniteCount(), 1u);
    const Volume planes = loadVolumePlanes(path, 0, 1).planes;
    EXPECT_EQ(planes.dims, (std::array<int, 3>{5, 4, 2}));
    EXPECT_EQ(planes.nonFiniteCount(), 0u);
    EXPECT_EQ(loadVolumePlanes(path, 1, 2).planes.nonFiniteCount(), 1u);
}

TEST(VolumePlanes, RefusesPlanesOutsideTheGridAndShortFiles) {
    TempDir dir;
    const std::string data = encode(fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    const std::string path =
        dir.write("v.nrrd", vots::test::nrrdHeader("short", "raw", "endian: little\n") + "\n" + data);
    EXPECT_THROW(loadVolumePlanes(path, 0, 3), InputError);
    EXPECT_THROW(loadVolumePlanes(path, 2, 1), InputError);
    // The planes asked for are there, but the file is short of the whole payload: refused alike.
    const std::string cut = dir.write("cut.nrrd", vots::test::nrrdHeader("short", "raw", "endian: little\n") +
                                                      "\n" + data.substr(0, 50));
    EXPECT_THROW(loadVolumePlanes(cut, 0, 0), InputError);
    EXPECT_THROW(loadVolumePlanes(dir.file("missing.nrrd"), 0, 0), InputError);
    EXPECT_THROW(readsOnlyPlanes(dir.write("v.xyz", data)), InputError);
}

} // namespace
