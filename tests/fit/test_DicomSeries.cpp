// DICOM series through GDCM: values in real units, spacing, slice order, orientation, compressed syntaxes.
#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"

#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace {

using namespace vots::fit;
using vots::test::DicomFileOrder;
using vots::test::DicomWriteOptions;
using vots::test::TempDir;
using vots::test::writeDicomSeries;

/// Distinct along every axis, so a flipped or shuffled axis changes the values; HU-like range.
Volume ramp(const std::array<int, 3>& dims = {9, 7, 6},
            const std::array<double, 3>& spacing = {0.5, 0.7, 2.0}) {
    return vots::test::sampleVolume(
        dims, [](int x, int y, int z) { return 10.0 * x + 3.0 * y - 70.0 * z - 600.0; }, spacing);
}

void expectSameSamples(const Volume& a, const Volume& b) {
    ASSERT_EQ(a.dims, b.dims);
    for (int z = 0; z < a.dims[2]; ++z)
        for (int y = 0; y < a.dims[1]; ++y)
            for (int x = 0; x < a.dims[0]; ++x)
                ASSERT_EQ(a.at(x, y, z), b.at(x, y, z)) << x << "," << y << "," << z;
}

TEST(DicomSeries, ValuesInHounsfieldSpacingAndOrientation) {
    TempDir dir;
    const Volume source = ramp();
    DicomWriteOptions o;
    o.storeSigned = false; // unsigned pixels, intercept -1024: the usual CT encoding
    o.intercept = -1024;
    o.bitsStored = 12;
    o.origin = {-20.5, 11.0, 300.0};
    o.junkFile = true;
    writeDicomSeries(source, dir.file("ct"), o);

    const Volume v = loadVolume(dir.file("ct"), std::nullopt, SampleStorage::Source);
    expectSameSamples(v, source);
    EXPECT_EQ(v.at(0, 0, 0), -600.f); // HU after the rescale, not the stored 424
    EXPECT_DOUBLE_EQ(v.spacing[0], 0.5);
    EXPECT_DOUBLE_EQ(v.spacing[1], 0.7);
    EXPECT_NEAR(v.spacing[2], 2.0, 1e-9);
    EXPECT_EQ(v.origin, (std::array<double, 3>{-20.5, 11.0, 300.0}));
    EXPECT_TRUE(v.orientationKnown);
    EXPECT_EQ(v.patientAxes[0], (std::array<double, 3>{1, 0, 0}));
    EXPECT_EQ(v.patientAxes[1], (std::array<double, 3>{0, 1, 0}));
    EXPECT_EQ(v.patientAxes[2], (std::array<double, 3>{0, 0, 1}));
    // Integral rescale of 16-bit pixels: held compactly as int16, as the NRRD CT is.
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    EXPECT_TRUE(std::holds_alternative<std::vector<std::int16_t>>(v.compact));
    EXPECT_EQ(v.name, "ct");
}

TEST(DicomSeries, FractionalRescaleLoadsAsFloat) {
    TempDir dir;
    const Volume source = ramp();
    DicomWriteOptions o;
    o.slope = 0.5;
    o.intercept = -1000.5;
    writeDicomSeries(source, dir.file("s"), o);
    const Volume v = loadVolume(dir.file("s"), std::nullopt, SampleStorage::Source);
    EXPECT_EQ(v.sourceType, ScalarType::Float32);
    EXPECT_FALSE(v.isCompact());
    expectSameSamples(v, source);
}

TEST(DicomSeries, OrderComesFromPositionsNotFileNames) {
    TempDir dir;
    const Volume source = ramp();
    const std::map<std::string, DicomFileOrder> orders = {{"ascending", DicomFileOrder::Ascending},
                                                          {"descending", DicomFileOrder::Descending},
                                                          {"shuffled", DicomFileOrder::Shuffled}};
    for (const auto& [name, order] : orders) {
        DicomWriteOptions o;
        o.order = order;
        writeDicomSeries(source, dir.file(name), o);
        const Volume v = loadVolume(dir.file(name));
        SCOPED_TRACE(name);
        expectSameSamples(v, source);
        EXPECT_EQ(v.origin, (std::array<double, 3>{0, 0, 0}));
    }
}

TEST(DicomSeries, FeetFirstNormalBecomesTheThirdAxis) {
    TempDir dir;
    const Volume source = ramp();
    DicomWriteOptions o;
    o.orientation = {1, 0, 0, 0, -1, 0}; // row x column points to the feet: positions fall along z
    o.origin = {0, 0, 50};
    o.order = DicomFileOrder::Shuffled;
    writeDicomSeries(source, dir.file("ff"), o);
    const Volume v = loadVolume(dir.file("ff"));
    expectSameSamples(v, source);
    EXPECT_EQ(v.patientAxes[1], (std::array<double, 3>{0, -1, 0}));
    EXPECT_EQ(v.patientAxes[2], (std::array<double, 3>{0, 0, -1}));
    EXPECT_EQ(v.origin, (std::array<double, 3>{0, 0, 50}));
    EXPECT_NEAR(v.spacing[2], 2.0, 1e-9);
}

TEST(DicomSeries, CompressedSeriesEqualTheUncompressedOne) {
    TempDir dir;
    const Volume source = ramp({16, 12, 5});
    writeDicomSeries(source, dir.file("explicit"), {});
    const Volume reference = loadVolume(dir.file("explicit"));
    expectSameSamples(reference, source);
    for (const char* syntax : {"implicit", "rle", "jpeg-lossless", "jpeg-ls", "jpeg2000"}) {
        DicomWriteOptions o;
        o.syntax = syntax;
        o.storeSigned = false;
        o.intercept = -1024;
        writeDicomSeries(source, dir.file(syntax), o);
        SCOPED_TRACE(syntax);
        const Volume v = loadVolume(dir.file(syntax));
        expectSameSamples(v, reference);
        EXPECT_EQ(v.spacing, reference.spacing);
    }
}

TEST(DicomSeries, HeaderInfoMatchesTheLoad) {
    TempDir dir;
    DicomWriteOptions o;
    o.syntax = "rle";
    writeDicomSeries(ramp(), dir.file("t"), o);
    const VolumeHeaderInfo info = volumeHeaderInfo(dir.file("t"));
    const Volume v = loadVolume(dir.file("t"), std::nullopt, SampleStorage::Source);
    EXPECT_EQ(info.dims, (std::array<std::uint64_t, 3>{9, 7, 6}));
    EXPECT_EQ(info.sourceType, ScalarType::Int16);
    EXPECT_EQ(v.sourceType, info.sourceType);
    EXPECT_EQ(info.describe(), "9x7x6 int16");
}

TEST(DicomSeries, SeveralSeriesNeedAChoice) {
    TempDir dir;
    DicomWriteOptions a;
    a.seriesUid = "1.2.3.4.10";
    a.description = "bone kernel";
    a.filePrefix = "a";
    DicomWriteOptions b;
    b.seriesUid = "1.2.3.4.20";
    b.description = "soft kernel";
    b.filePrefix = "b";
    writeDicomSeries(ramp(), dir.file("two"), a);
    writeDicomSeries(ramp({9, 7, 4}), dir.file("two"), b);

    const auto series = listDicomSeries(dir.file("two"));
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[1].uid, "1.2.3.4.20");
    EXPECT_EQ(series[1].description, "soft kernel");
    EXPECT_EQ(series[1].sliceCount, 4);
    try {
        loadVolume(dir.file("two"));
        ADD_FAILURE() << "no error for two series";
    } catch (const InputError& e) {
        const std::string m = e.what();
        for (const char* part : {"2 DICOM series", "--series", "1.2.3.4.10 \"bone kernel\" (6 slices)",
                                 "1.2.3.4.20 \"soft kernel\" (4 slices)"})
            EXPECT_NE(m.find(part), std::string::npos) << m;
    }
    EXPECT_EQ(loadVolume(dir.file("two"), std::nullopt, SampleStorage::Float, "1.2.3.4.20").dims[2], 4);
    EXPECT_EQ(volumeHeaderInfo(dir.file("two"), std::nullopt, "1.2.3.4.10").dims[2], 6u);
    EXPECT_THROW(loadVolume(dir.file("two"), std::nullopt, SampleStorage::Float, "9.9"), InputError);
}

void expectError(const std::string& folder, const std::string& problem) {
    for (const bool headerOnly : {false, true}) {
        try {
            if (headerOnly)
                (void)volumeHeaderInfo(folder);
            else
                (void)loadVolume(folder);
            ADD_FAILURE() << "no InputError for " << folder << " (expected '" << problem << "')";
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(problem), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
}

TEST(DicomSeries, BadSeriesGiveOneLineNamingTheProblem) {
    TempDir dir;
    DicomWriteOptions drop;
    drop.dropSlice = 3;
    drop.order = DicomFileOrder::Shuffled;
    writeDicomSeries(ramp(), dir.file("missing"), drop);
    expectError(dir.file("missing"), "missing slice");

    DicomWriteOptions resize;
    resize.resizeSlice = 1;
    writeDicomSeries(ramp(), dir.file("sizes"), resize);
    expectError(dir.file("sizes"), "mixed image sizes");

    DicomWriteOptions cut;
    cut.truncateSlice = 4;
    writeDicomSeries(ramp(), dir.file("cut"), cut);
    expectError(dir.file("cut"), "truncated");

    std::filesystem::create_directories(dir.file("empty"));
    expectError(dir.file("empty"), "holds no DICOM images");
    std::filesystem::create_directories(dir.file("junk"));
    dir.write("junk/notes.txt", "not DICOM\n");
    dir.write("junk/image.dcm", std::string(200, 'x'));
    expectError(dir.file("junk"), "holds no DICOM images");
}

TEST(DicomSeries, DamagedHeaderIsNotSkipped) {
    TempDir dir;
    writeDicomSeries(ramp(), dir.file("h"), {});
    const std::string file = dir.file("h/slice-0002.dcm");
    std::filesystem::resize_file(file, 200); // past the DICM signature, inside the meta header
    try {
        (void)loadVolume(dir.file("h"));
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("slice-0002.dcm: is a"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("DICOM file"), std::string::npos) << e.what();
    }
}

// Under mpirun each rank loads its planes of a series: the same bits as cutting the whole series, with
// only the planes' slice files decoded.
TEST(DicomSeries, PlanesAreTheCutOfTheWholeSeries) {
    TempDir dir;
    const Volume source = ramp({9, 7, 5});
    DicomWriteOptions o;
    o.order = DicomFileOrder::Shuffled; // planes follow the positions, not the file names
    o.slicesAlongNormal = false;        // and a third axis against the normal
    o.origin = {3.25, -7.5, 41.0};
    writeDicomSeries(source, dir.file("ct"), o);
    EXPECT_TRUE(readsOnlyPlanes(dir.file("ct")));
    for (const SampleStorage storage : {SampleStorage::Float, SampleStorage::Source}) {
        const Volume whole = loadVolume(dir.file("ct"), std::nullopt, storage);
        for (int first = 0; first < 5; ++first) {
            for (int last = first; last < 5; ++last) {
                SCOPED_TRACE("planes " + std::to_string(first) + ".." + std::to_string(last));
                const Volume cut = planesOf(whole, first, last);
                const PlanesOfGrid slab =
                    loadVolumePlanes(dir.file("ct"), first, last, std::nullopt, storage);
                EXPECT_EQ(slab.planes.dims, cut.dims);
                EXPECT_EQ(std::memcmp(slab.planes.origin.data(), cut.origin.data(), sizeof cut.origin), 0);
                EXPECT_EQ(slab.planes.spacing, cut.spacing);
                EXPECT_EQ(slab.planes.patientAxes, cut.patientAxes);
                EXPECT_EQ(slab.planes.name, cut.name);
                EXPECT_EQ(slab.planes.values, cut.values);
                EXPECT_EQ(slab.planes.compact, cut.compact);
                EXPECT_EQ(slab.whole.dims, whole.dims);
                EXPECT_EQ(slab.whole.origin, whole.origin);
                EXPECT_TRUE(slab.whole.values.empty() && !slab.whole.isCompact());
            }
        }
    }
    EXPECT_THROW(loadVolumePlanes(dir.file("ct"), 3, 5), InputError);
}

TEST(DicomSeries, PlanesDecodeOnlyTheirOwnSlices) {
    TempDir dir;
    DicomWriteOptions o;
    o.syntax = "rle";
    writeDicomSeries(ramp(), dir.file("ct"), o);
    // Slice 4's headers stay valid, its RLE header announces 15 segments at offsets past the data:
    // only decoding its pixels can find that.
    const std::string damaged = dir.file("ct") + "/slice-0005.dcm";
    std::string bytes;
    {
        std::ifstream in(damaged, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::string itemTag("\xfe\xff\x00\xe0", 4);
    const std::size_t fragment = bytes.rfind(itemTag);
    ASSERT_NE(fragment, std::string::npos);
    for (std::size_t i = 0; i < 16; ++i) {
        const std::uint32_t word = i == 0 ? 15u : 0x7fff0000u + static_cast<std::uint32_t>(i);
        std::memcpy(bytes.data() + fragment + 8 + 4 * i, &word, 4);
    }
    std::ofstream(damaged, std::ios::binary) << bytes;
    try {
        loadVolume(dir.file("ct"));
        ADD_FAILURE() << "the damaged slice was not found";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("slice-0005.dcm"), std::string::npos) << e.what();
    }
    const Volume planes = loadVolumePlanes(dir.file("ct"), 0, 3).planes;
    EXPECT_EQ(planes.dims, (std::array<int, 3>{9, 7, 4}));
    expectSameSamples(planes, planesOf(ramp(), 0, 3));
    EXPECT_THROW(loadVolumePlanes(dir.file("ct"), 3, 4), InputError);
}

} // namespace
