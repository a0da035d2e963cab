// Volume input on hostile files: every malformed case must give one clear InputError line, never a crash.
#include "vots/fit/Error.h"
#include "vots/fit/VolumeLoad.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

namespace {

using namespace vots::fit;
using vots::test::encode;
using vots::test::niftiHeader;
using vots::test::nrrdHeader;
using vots::test::TempDir;

// The load must throw InputError whose one-line message names `file` and contains `problem`.
void expectInputError(const std::function<void()>& load, const std::string& file,
                      const std::string& problem) {
    try {
        load();
        ADD_FAILURE() << "no InputError for " << file << " (expected '" << problem << "')";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(file), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

void expectLoadError(const std::string& path, const std::string& problem) {
    expectInputError([&] { loadVolume(path); }, std::filesystem::path(path).filename().string(), problem);
}

std::string int16Data() {
    return encode(vots::test::fixtureValues(ScalarType::Int16), ScalarType::Int16, false);
}

std::string int16Nrrd(const std::string& sizes = "5 4 3") {
    return "NRRD0004\ntype: short\ndimension: 3\nsizes: " + sizes + "\nendian: little\nencoding: raw\n\n";
}

TEST(VolumeLoadErrors, MissingFilesAndFolders) {
    TempDir dir;
    for (const char* name :
         {"absent.nrrd", "absent.nhdr", "absent.nii", "absent.nii.gz", "absent.mhd", "absent.mha"})
        expectLoadError(dir.file(name), "no such file");
    RawLayout layout;
    layout.dims = {1, 1, 1};
    expectInputError([&] { loadVolume(dir.file("absent.raw"), layout); }, "absent.raw", "no such file");
    std::filesystem::create_directory(dir.path() / "folder.nrrd");
    expectLoadError(dir.file("folder.nrrd"), "folder");
    std::filesystem::create_directory(dir.path() / "folder.nii.gz");
    expectLoadError(dir.file("folder.nii.gz"), "folder");
    expectLoadError(dir.write("volume.xyz", "data"), "unknown volume format");
}

TEST(VolumeLoadErrors, EmptyFiles) {
    TempDir dir;
    expectLoadError(dir.write("e.nrrd", ""), "not a NRRD file");
    expectLoadError(dir.write("e.nii", ""), "too short");
    expectLoadError(dir.write("e.nii.gz", ""), "too short");
    expectLoadError(dir.write("e.mhd", ""), "no ElementDataFile");
}

TEST(VolumeLoadErrors, TruncatedData) {
    TempDir dir;
    const std::string data = int16Data();
    expectLoadError(dir.write("t.nrrd", int16Nrrd() + data.substr(0, data.size() - 1)), "truncated");
    const std::string nifti = niftiHeader({}) + data;
    expectLoadError(dir.write("t.nii", nifti.substr(0, nifti.size() - 2)), "truncated");
    expectLoadError(dir.write("h.nii", nifti.substr(0, 200)), "too short");
    vots::test::appendGzip(dir.file("t.nii.gz"), nifti.substr(0, nifti.size() - 2));
    expectLoadError(dir.file("t.nii.gz"), "too short");
    dir.write("t.raw", data.substr(0, 10));
    const std::string mhd = dir.write("t.mhd", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
                                               "ElementDataFile = t.raw\n");
    expectInputError([&] { loadVolume(mhd); }, "t.raw", "truncated"); // names the file that is short
    RawLayout layout;
    layout.dims = vots::test::FIXTURE_DIMS;
    layout.type = ScalarType::Int16;
    expectInputError([&] { loadRaw(dir.file("t.raw"), layout); }, "t.raw", "needs 120");
}

TEST(VolumeLoadErrors, HeadersThatLieAboutTheSize) {
    TempDir dir;
    const std::string data = int16Data();
    // More data than the sizes describe: wrong dims, not silently cropped.
    expectLoadError(dir.write("big.nrrd", int16Nrrd("5 4 2") + data), "header describes");
    expectLoadError(dir.write("small.nrrd", int16Nrrd("5 4 4") + data), "truncated");
    vots::test::NiftiSpec spec;
    spec.dim[3] = 2;
    expectLoadError(dir.write("big.nii", niftiHeader(spec) + data), "header describes");
    vots::test::appendGzip(dir.file("big.nii.gz"), niftiHeader(spec) + data);
    expectLoadError(dir.file("big.nii.gz"), "longer than the header says");
    const std::string gz = dir.write("g.nrrd", nrrdHeader("short", "gzip", "endian: little\n\n"));
    vots::test::appendGzip(gz, data + "xx");
    expectLoadError(gz, "longer than the header says");
    spec = {};
    spec.bitpix = 8; // datatype 4 is 16 bits
    expectLoadError(dir.write("bitpix.nii", niftiHeader(spec) + data), "bitpix");
    spec = {};
    spec.voxOffset = 100.0f;
    expectLoadError(dir.write("vox.nii", niftiHeader(spec) + data), "vox_offset");
    const std::string packed = vots::test::zlibBytes(data);
    expectLoadError(
        dir.write("c.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\nCompressedData = True\n"
                           "CompressedDataSize = " +
                               std::to_string(packed.size() + 100) + "\nElementDataFile = LOCAL\n" + packed),
        "CompressedDataSize");
}

TEST(VolumeLoadErrors, BadDimensions) {
    TempDir dir;
    const std::string data = int16Data();
    expectLoadError(dir.write("zero.nrrd", int16Nrrd("5 0 3") + data), "must be positive");
    expectLoadError(dir.write("neg.nrrd", int16Nrrd("5 -4 3") + data), "must be positive");
    expectLoadError(dir.write("overflow.nrrd", int16Nrrd("2000000 2000000 2000000") + data),
                    "exceed the limit");
    expectLoadError(dir.write("huge.nrrd", int16Nrrd("9223372036854775807 9223372036854775807 2") + data),
                    "exceed the limit");
    expectLoadError(dir.write("toolong.nrrd", int16Nrrd("99999999999999999999999 1 1") + data),
                    "bad integer");
    expectLoadError(dir.write("two.nrrd", int16Nrrd("5 4") + data), "needs 3 integers");
    expectLoadError(dir.write("dim2.nrrd", "NRRD0004\ntype: short\ndimension: 2\nsizes: 5 12\n"
                                           "endian: little\nencoding: raw\n\n" +
                                               data),
                    "only 3D");
    vots::test::NiftiSpec spec;
    spec.dim[2] = -4;
    expectLoadError(dir.write("neg.nii", niftiHeader(spec) + data), "must be positive");
    spec = {};
    spec.dim[0] = 4;
    spec.dim[4] = 7; // a time series whose payload is one frame
    expectLoadError(dir.write("series.nii", niftiHeader(spec) + data), "truncated");
    spec.dim[0] = 8; // beyond NIfTI's 7 dimensions
    expectLoadError(dir.write("rank8.nii", niftiHeader(spec) + data), "only 3D and 4D");
    spec = {};
    spec.dim[0] = 2;
    expectLoadError(dir.write("flat.nii", niftiHeader(spec) + data), "only 3D");
    expectLoadError(dir.write("big.mhd", "NDims = 3\nDimSize = 65536 65536 65536\nElementType = MET_UCHAR\n"
                                         "ElementDataFile = LOCAL\n"),
                    "exceed the limit");
    expectLoadError(dir.write("nd.mhd", "NDims = 4\nDimSize = 5 4 3 1\nElementType = MET_UCHAR\n"
                                        "ElementDataFile = LOCAL\n"),
                    "only 3D");
    RawLayout layout;
    layout.dims = {1 << 20, 1 << 20, 1};
    expectInputError([&] { loadRaw(dir.write("r.raw", data), layout); }, "r.raw", "exceed the limit");
    layout.dims = {5, 4, 3};
    layout.spacing = {1.0, 0.0, 1.0};
    expectInputError([&] { loadRaw(dir.file("r.raw"), layout); }, "r.raw", "spacing");
}

TEST(VolumeLoadErrors, CorruptCompressedStreams) {
    TempDir dir;
    const std::string data = int16Data();
    // A valid gzip NRRD, then copies with a damaged deflate body and with a cut-off stream.
    const std::string good = dir.write("good.nrrd", nrrdHeader("short", "gzip", "endian: little\n\n"));
    vots::test::appendGzip(good, data);
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t body = bytes.find("\n\n") + 2 + 10; // past the 10-byte gzip member header
    std::string damaged = bytes;
    for (std::size_t i = body; i < body + 8; ++i)
        damaged[i] = static_cast<char>(damaged[i] ^ 0x5A);
    expectLoadError(dir.write("damaged.nrrd", damaged), "compressed data");
    expectLoadError(dir.write("cut.nrrd", bytes.substr(0, bytes.size() - 20)), "truncated");
    std::string badCrc = bytes;
    badCrc[badCrc.size() - 6] = static_cast<char>(badCrc[badCrc.size() - 6] ^ 1); // inside the CRC-32
    expectLoadError(dir.write("crc.nrrd", badCrc), "corrupt");
    expectLoadError(dir.write("junk.nrrd", bytes + "junk"), "after the compressed stream");
    expectLoadError(dir.write("g.nii.gz", "\x1f\x8b not really gzip"), "corrupt");
    expectLoadError(dir.write("z.mha",
                              "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\nCompressedData = True\n"
                              "ElementDataFile = LOCAL\nthis is not zlib"),
                    "corrupt");
}

TEST(VolumeLoad, NonFiniteFloatSamplesLoadAsNoData) {
    TempDir dir;
    std::vector<double> values = vots::test::fixtureValues(ScalarType::Float32);
    values[3] = std::numeric_limits<double>::quiet_NaN();
    values[7] = std::numeric_limits<double>::infinity();
    values[8] = -std::numeric_limits<double>::infinity();
    const Volume nan = loadVolume(dir.write("nan.nrrd", nrrdHeader("float", "raw", "endian: little\n\n") +
                                                            encode(values, ScalarType::Float32, false)));
    EXPECT_EQ(nan.nonFiniteCount(), 3u);
    EXPECT_TRUE(std::isnan(nan.values[3]));
    EXPECT_EQ(nan.values[7], std::numeric_limits<float>::infinity());
    EXPECT_EQ(nan.values[9], static_cast<float>(values[9]));
    // The range is of the finite samples only.
    std::vector<double> finite;
    for (const double v : values)
        if (std::isfinite(v)) finite.push_back(v);
    EXPECT_EQ(nan.valueRange()[0], static_cast<float>(*std::min_element(finite.begin(), finite.end())));
    EXPECT_EQ(nan.valueRange()[1], static_cast<float>(*std::max_element(finite.begin(), finite.end())));
    values = vots::test::fixtureValues(ScalarType::Float64);
    values[0] = -1e300; // beyond float range: an infinity, no data
    vots::test::NiftiSpec spec;
    spec.datatype = 64;
    spec.bitpix = 64;
    const Volume range =
        loadVolume(dir.write("range.nii", niftiHeader(spec) + encode(values, ScalarType::Float64, false)));
    EXPECT_EQ(range.values[0], -std::numeric_limits<float>::infinity());
    EXPECT_EQ(range.nonFiniteCount(), 1u);
}

TEST(VolumeLoadErrors, ScalingBeyondFloatRange) {
    TempDir dir;
    vots::test::NiftiSpec spec;
    spec.sclSlope = 1e38f; // scaling pushes int16 samples beyond float range
    expectLoadError(dir.write("slope.nii", niftiHeader(spec) + int16Data()), "float range");
}

TEST(VolumeLoadErrors, UnknownTypesAndEncodings) {
    TempDir dir;
    const std::string data = int16Data();
    expectLoadError(dir.write("i64.nrrd", nrrdHeader("int64", "raw", "endian: little\n\n") + data),
                    "unsupported type 'int64'");
    expectLoadError(dir.write("blob.nrrd", nrrdHeader("block", "raw", "\n") + data), "unsupported type");
    expectLoadError(
        dir.write("notype.nrrd", "NRRD0004\ndimension: 3\nsizes: 5 4 3\nencoding: raw\n\n" + data),
        "missing 'type'");
    expectLoadError(dir.write("bz.nrrd", nrrdHeader("short", "bzip2", "endian: little\n\n") + data),
                    "unsupported encoding");
    expectLoadError(dir.write("noend.nrrd", nrrdHeader("short", "raw", "\n") + data), "missing 'endian'");
    expectLoadError(dir.write("magic.nrrd", "P5\n5 4\n255\n" + data), "not a NRRD file");
    expectLoadError(dir.write("bad.nrrd", "NRRD0004\nthis line has no colon\n\n" + data), "bad header line");
    vots::test::NiftiSpec spec;
    spec.datatype = 32; // complex64
    spec.bitpix = 64;
    expectLoadError(dir.write("complex.nii", niftiHeader(spec) + data), "unsupported NIfTI datatype 32");
    spec = {};
    spec.magic = std::string("ni1\0", 4);
    expectLoadError(dir.write("pair.nii", niftiHeader(spec) + data), "pair");
    expectLoadError(dir.write("junk.nii", std::string(400, 'j')), "not a NIfTI file");
    expectLoadError(dir.write("long.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_LONG\n"
                                          "ElementDataFile = LOCAL\n" +
                                              data),
                    "unsupported ElementType 'MET_LONG'");
    expectLoadError(dir.write("rgb.mha", "NDims = 3\nDimSize = 5 4 3\nElementNumberOfChannels = 3\n"
                                         "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" +
                                             data),
                    "ElementNumberOfChannels");
    expectInputError([] { parseScalarType("quaternion"); }, "quaternion", "unknown sample type");
}

TEST(VolumeLoadErrors, MissingOrUnusableDataFiles) {
    TempDir dir;
    expectLoadError(dir.write("d.nhdr", nrrdHeader("short", "raw", "endian: little\ndata file: gone.raw\n")),
                    "data file 'gone.raw'");
    expectLoadError(dir.write("nodata.nhdr", nrrdHeader("short", "raw", "endian: little\n")), "no data");
    std::filesystem::create_directory(dir.path() / "sub.raw");
    expectLoadError(dir.write("dir.nhdr", nrrdHeader("short", "raw", "endian: little\ndata file: sub.raw\n")),
                    "folder");
    expectLoadError(
        dir.write("p.nhdr", nrrdHeader("short", "raw", "endian: little\ndata file: s%s.raw 1 3 1\n")),
        "exactly one %d");
    expectLoadError(dir.write("m.mhd", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
                                       "ElementDataFile = gone.raw\n"),
                    "data file 'gone.raw'");
}

// Every cut-off copy of a small valid file must throw InputError; byte flips must load or throw it.
TEST(VolumeLoadErrors, TruncationsAndByteFlipsNeverCrash) {
    TempDir dir;
    const std::string data = int16Data();
    const std::string gzNrrd = dir.write("src.nrrd", nrrdHeader("short", "gzip", "endian: little\n\n"));
    vots::test::appendGzip(gzNrrd, data);
    vots::test::appendGzip(dir.file("src.nii.gz"), niftiHeader({}) + data);
    const std::string mha = dir.write("src.mha", "NDims = 3\nDimSize = 5 4 3\nElementType = MET_SHORT\n"
                                                 "CompressedData = True\nElementDataFile = LOCAL\n" +
                                                     vots::test::zlibBytes(data));
    for (const std::string& source : {gzNrrd, dir.file("src.nii.gz"), mha}) {
        SCOPED_TRACE(source);
        std::ifstream in(source, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string name =
            "fuzz" + std::string(source.ends_with(".nii.gz")
                                     ? ".nii.gz"
                                     : std::filesystem::path(source).extension().string());
        // Every byte of the headers, then every 5th: the compressed body has no structure to aim at.
        for (std::size_t i = 0; i < bytes.size(); i += i < 400 ? 1 : 5) {
            const std::string cut = dir.write(name, bytes.substr(0, i));
            EXPECT_THROW(loadVolume(cut), InputError) << "cut at " << i;
            std::string flipped = bytes;
            flipped[i] = static_cast<char>(flipped[i] ^ (1 << (i % 8)));
            try {
                loadVolume(dir.write(name, flipped));
            } catch (const InputError&) {
            }
        }
    }
}

} // namespace
