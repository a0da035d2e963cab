// volumeHeaderInfo agrees with loadVolume on every format without reading samples; the memory estimate,
// memory sizes as text and the default budget.
#include "VolumeFixtures.h"

#include "FuzzCorpus.h"
#include "TempDir.h"
#include "vots/fit/Error.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

namespace vots::test {
namespace {

constexpr std::uint64_t GIB = std::uint64_t{1} << 30;

void expectSameAsLoad(const std::string& path, const std::optional<fit::RawLayout>& raw = std::nullopt) {
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(path, raw);
    const fit::Volume volume = fit::loadVolume(path, raw);
    for (int a = 0; a < 3; ++a)
        EXPECT_EQ(header.dims[a], static_cast<std::uint64_t>(volume.dims[a])) << path << " axis " << a;
    EXPECT_EQ(header.sourceType, volume.sourceType) << path;
    EXPECT_EQ(header.sampleCount(), volume.sampleCount()) << path;
}

TEST(VolumeHeader, AgreesWithTheReaderOnEveryFormat) {
    TempDir dir;
    const std::string samples = encode(fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    expectSameAsLoad(dir.write("a.nrrd", nrrdHeader("short", "raw", "endian: little\n\n") + samples));
    dir.write("d.raw", samples);
    expectSameAsLoad(dir.write("d.nhdr", nrrdHeader("int16", "raw", "endian: little\ndata file: d.raw\n")));
    appendGzip(dir.file("g.raw.gz"), samples);
    expectSameAsLoad(
        dir.write("g.nhdr", nrrdHeader("int16", "gzip", "endian: little\ndata file: g.raw.gz\n")));

    NiftiSpec spec;
    expectSameAsLoad(dir.write("n.nii", niftiHeader(spec) + samples));
    spec.bigEndian = true;
    expectSameAsLoad(dir.write(
        "b.nii", niftiHeader(spec) + encode(fixtureValues(ScalarType::Int16), ScalarType::Int16, true)));
    spec.bigEndian = false;
    appendGzip(dir.file("z.nii.gz"), niftiHeader(spec) + samples);
    expectSameAsLoad(dir.file("z.nii.gz"));

    const std::string meta = "ObjectType = Image\nNDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n";
    expectSameAsLoad(dir.write("m.mha", meta + "ElementDataFile = LOCAL\n" + samples));
    expectSameAsLoad(dir.write("m.mhd", meta + "ElementDataFile = d.raw\n"));

    fit::RawLayout raw;
    raw.dims = FIXTURE_DIMS;
    raw.type = ScalarType::Int16;
    expectSameAsLoad(dir.file("d.raw"), raw);

    for (const char* name : {"blobs_64x64x64_uint8.nrrd", "cranium-quarter_64x64x108_int16.nrrd",
                             "orbital_64x64x64_float32.nrrd"}) {
        const std::string path = std::string(VOTS_TEST_DATA_DIR) + "/" + name;
        expectSameAsLoad(path);
    }
}

// Over the fuzz inputs (hostile headers): the header reader throws only InputError, and every file the
// reader loads is also sized by the header reader, with the same grid, so none is refused wrongly.
TEST(VolumeHeader, AgreesWithTheReaderOnTheFuzzInputs) {
    for (const auto& [target, extension] : {std::pair{"fuzz_nrrd", ".nrrd"}, std::pair{"fuzz_nifti", ".nii"},
                                            std::pair{"fuzz_metaimage", ".mha"}}) {
        const auto inputs = fuzzInputs(target);
        ASSERT_FALSE(inputs.empty()) << target;
        int loaded = 0;
        for (const auto& [name, bytes] : inputs) {
            SCOPED_TRACE(std::string(target) + "/" + name);
            const TempDir dir;
            const std::string path = dir.write(std::string("input") + extension, bytes);
            std::optional<fit::VolumeHeaderInfo> header;
            try {
                header = fit::volumeHeaderInfo(path);
            } catch (const fit::InputError&) {
            }
            try {
                const fit::Volume volume = fit::loadVolume(path);
                ++loaded;
                ASSERT_TRUE(header.has_value()) << "loads, but its header was refused";
                for (int a = 0; a < 3; ++a)
                    EXPECT_EQ(header->dims[a], static_cast<std::uint64_t>(volume.dims[a]));
                EXPECT_EQ(header->sourceType, volume.sourceType);
            } catch (const fit::InputError&) {
            }
        }
        EXPECT_GT(loaded, 0) << target << ": no seed loads, so nothing was compared";
    }
}

TEST(VolumeHeader, AHugeAnnouncedVolumeIsReportedWithoutReadingIt) {
    TempDir dir;
    dir.write("tiny.raw", std::string(8, '\0'));
    const std::string nhdr = dir.write(
        "huge.nhdr", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n"
                     "data file: tiny.raw\n");
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(nhdr);
    EXPECT_EQ(header.sampleCount(), std::uint64_t{1000000000000000});
    EXPECT_EQ(header.describe(), "100000x100000x100000 uint8");
    EXPECT_GT(fit::estimateLoadAndFitBytes(header), std::uint64_t{1000} * 1000 * GIB); // over a petabyte

    NiftiSpec spec;
    spec.dim = {3, 32767, 32767, 32767, 1, 1, 1, 1};
    const fit::VolumeHeaderInfo nifti = fit::volumeHeaderInfo(dir.write("huge.nii", niftiHeader(spec)));
    EXPECT_EQ(nifti.sampleCount(), std::uint64_t{32767} * 32767 * 32767);
    EXPECT_EQ(nifti.storedBytes(), 2 * nifti.sampleCount());

    // Products past 2^64 saturate rather than wrap to a small, admissible number.
    const std::string mha = dir.write("wrap.mha", "NDims = 3\nDimSize = 4294967296 4294967296 4294967296\n"
                                                  "ElementType = MET_DOUBLE\nElementDataFile = LOCAL\n");
    const fit::VolumeHeaderInfo wrapped = fit::volumeHeaderInfo(mha);
    EXPECT_EQ(wrapped.sampleCount(), std::numeric_limits<std::uint64_t>::max());
    EXPECT_EQ(fit::estimateLoadAndFitBytes(wrapped), std::numeric_limits<std::uint64_t>::max());
}

TEST(VolumeHeader, MalformedHeadersAreInputErrors) {
    TempDir dir;
    EXPECT_THROW(fit::volumeHeaderInfo(dir.write("a.nrrd", "NRRD0004\ntype: short\ndimension: 3\n\n")),
                 fit::InputError); // no sizes
    EXPECT_THROW(
        fit::volumeHeaderInfo(dir.write("b.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 0 4\n\n")),
        fit::InputError);
    EXPECT_THROW(
        fit::volumeHeaderInfo(dir.write("c.nrrd", "NRRD0004\ntype: short\ndimension: 2\nsizes: 4 4\n\n")),
        fit::InputError);
    EXPECT_THROW(fit::volumeHeaderInfo(dir.write("d.mha", "NDims = 3\nElementDataFile = LOCAL\n")),
                 fit::InputError);
    EXPECT_THROW(fit::volumeHeaderInfo(dir.write("e.nii", "short")), fit::InputError);
    EXPECT_THROW(fit::volumeHeaderInfo(dir.write("f.png", "x")), fit::InputError);
    EXPECT_THROW(fit::volumeHeaderInfo(dir.file("missing.nrrd")), fit::InputError);
}

TEST(MemoryEstimate, GrowsWithSamplesAndStoredBytesAndCoversTheLoadedVolume) {
    fit::VolumeHeaderInfo small{{64, 64, 64}, ScalarType::UInt8};
    fit::VolumeHeaderInfo wider{{64, 64, 64}, ScalarType::Float64};
    fit::VolumeHeaderInfo bigger{{512, 512, 1000}, ScalarType::Int16};
    EXPECT_LT(fit::estimateLoadAndFitBytes(small), fit::estimateLoadAndFitBytes(wider));
    EXPECT_LT(fit::estimateLoadAndFitBytes(wider), fit::estimateLoadAndFitBytes(bigger));
    for (const auto& h : {small, wider, bigger})
        EXPECT_GE(fit::estimateLoadAndFitBytes(h), fit::estimateLoadedVolumeBytes(h) + h.storedBytes());
    // The peaks of `vots fit --certify cells` with float samples (4.8 bytes a sample measured at
    // 512x512x432, bench/RESULTS.md "Fit memory"), 1.26 GB at 1000 and 3.8 GB at 3000 slices: an
    // estimate below them would admit what the kernel then kills.
    EXPECT_GE(fit::estimateLoadAndFitBytes(bigger), 1.26e9);
    const fit::VolumeHeaderInfo tallest{{512, 512, 3000}, ScalarType::Int16};
    EXPECT_GE(fit::estimateLoadAndFitBytes(tallest), 3.8e9);
}

TEST(MemoryEstimate, SourceStorageCountsTheBytesTheLoadHolds) {
    const fit::VolumeHeaderInfo int16s{{512, 512, 1000}, ScalarType::Int16};
    const std::uint64_t n = int16s.sampleCount();
    EXPECT_EQ(fit::estimateLoadedVolumeBytes(int16s), 4 * n); // floats unless told otherwise
    EXPECT_EQ(fit::estimateLoadedVolumeBytes(int16s, fit::SampleStorage::Float), 4 * n);
    EXPECT_EQ(fit::estimateLoadedVolumeBytes(int16s, fit::SampleStorage::Source), 2 * n);
    // Compact samples save their bytes in the whole estimate too, which still covers what stays held.
    EXPECT_EQ(fit::estimateLoadAndFitBytes(int16s, fit::SampleStorage::Float) -
                  fit::estimateLoadAndFitBytes(int16s, fit::SampleStorage::Source),
              2 * n);
    EXPECT_GE(fit::estimateLoadAndFitBytes(int16s, fit::SampleStorage::Source),
              fit::estimateLoadedVolumeBytes(int16s, fit::SampleStorage::Source) + int16s.storedBytes());
    // The peak of `vots fit --certify cells`, which holds them compact (bench/RESULTS.md "Fit memory").
    EXPECT_GE(fit::estimateLoadAndFitBytes(int16s, fit::SampleStorage::Source), 0.64e9);
    const fit::VolumeHeaderInfo uint8s{{64, 64, 64}, ScalarType::UInt8};
    EXPECT_EQ(fit::estimateLoadedVolumeBytes(uint8s, fit::SampleStorage::Source), uint8s.sampleCount());
    for (ScalarType wide :
         {ScalarType::Int32, ScalarType::UInt32, ScalarType::Float32, ScalarType::Float64}) {
        const fit::VolumeHeaderInfo h{{64, 64, 64}, wide};
        EXPECT_EQ(fit::estimateLoadedVolumeBytes(h, fit::SampleStorage::Source), 4 * h.sampleCount())
            << fit::scalarTypeName(wide);
    }
}

TEST(MemoryEstimate, ScaledNiftiSamplesAreCountedAsTheFloatsTheyLoadAs) {
    TempDir dir;
    const auto samples =
        vots::test::encode(vots::test::fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
    vots::test::NiftiSpec spec;
    const std::string plain = dir.write("plain.nii", vots::test::niftiHeader(spec) + samples);
    spec.sclSlope = 2.5f;
    spec.sclInter = -10.0f;
    const std::string scaled = dir.write("scaled.nii", vots::test::niftiHeader(spec) + samples);
    for (const auto& [path, bytes] : {std::pair{plain, 2u}, std::pair{scaled, 4u}}) {
        const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(path);
        EXPECT_EQ(fit::heldBytesPerSample(header, fit::SampleStorage::Source), bytes) << path;
        // The estimate agrees with what the load then holds.
        const fit::Volume volume = fit::loadVolume(path, std::nullopt, fit::SampleStorage::Source);
        EXPECT_EQ(volume.isCompact(), bytes == 2u) << path;
    }
}

TEST(MemorySize, ParsesUnitsAndRefusesNonsense) {
    EXPECT_EQ(fit::parseMemorySize("8G", "--memory-budget"), 8 * GIB);
    EXPECT_EQ(fit::parseMemorySize("8GB", "x"), 8 * GIB);
    EXPECT_EQ(fit::parseMemorySize("8GiB", "x"), 8 * GIB);
    EXPECT_EQ(fit::parseMemorySize("512m", "x"), std::uint64_t{512} << 20);
    EXPECT_EQ(fit::parseMemorySize("1.5G", "x"), 3 * GIB / 2);
    EXPECT_EQ(fit::parseMemorySize("64K", "x"), std::uint64_t{65536});
    EXPECT_EQ(fit::parseMemorySize("1T", "x"), 1024 * GIB);
    EXPECT_EQ(fit::parseMemorySize("123456789", "x"), std::uint64_t{123456789});
    for (const char* bad : {"", "0", "-1G", "8X", "G", "nan", "inf", "1e30T", "8 G B", "0.1"}) {
        try {
            fit::parseMemorySize(bad, "--memory-budget");
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const fit::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("--memory-budget"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(fit::formatBytes(3 * GIB / 2), "1.5 GB");
    EXPECT_EQ(fit::formatBytes(900), "900 B");
}

TEST(MemoryBudget, DefaultIsAboveWhatThisProcessHolds) {
    const std::uint64_t resident = fit::residentBytes();
    EXPECT_GT(resident, std::uint64_t{1} << 20); // a test binary holds at least a megabyte
    EXPECT_GT(fit::defaultMemoryBudget(), resident);
}

} // namespace
} // namespace vots::test
