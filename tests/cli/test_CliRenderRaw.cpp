// `vots render` of a headerless raw volume through the --raw-* options it shares with `vots fit`.
#include "CliRunner.h"
#include "Int16Bytes.h"
#include "TempDir.h"

#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace vots::test {
namespace {

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// The MRI's samples behind a 16-byte junk header, plus a detached NRRD header that describes the same
/// bytes: both inputs are the same volume, so every mode must render the same PNG from either.
struct RawHead {
    TempDir dir;
    std::string raw;
    std::string nhdr;
    RawHead() {
        const fit::Volume volume = fit::loadVolume(MRI_BRAIN);
        raw = dir.write("head.raw", std::string(16, 'h') + littleEndianInt16Bytes(volume));
        nhdr =
            dir.write("head.nhdr", "NRRD0004\ntype: int16\ndimension: 3\nsizes: 33 41 25\nendian: little\n"
                                   "spacings: 3 2 4\nencoding: raw\nbyte skip: 16\ndata file: head.raw\n\n");
    }
};

const std::vector<std::string> RAW_ARGS{"--raw-dims",    "33,41,25", "--raw-type",         "int16",
                                        "--raw-spacing", "3,2,4",    "--raw-header-bytes", "16"};

TEST(CliRenderRaw, RawInputRendersAsTheSameVolumeWithAHeader) {
    RawHead head;
    for (const char* mode : {"mip", "reference"}) {
        const std::string fromRaw = head.dir.file(std::string("raw-") + mode + ".png");
        const std::string fromNrrd = head.dir.file(std::string("nrrd-") + mode + ".png");
        std::vector<std::string> rawArgs{"render", head.raw, "-o",    fromRaw, "--size", "64x48",
                                         "--mode", mode,     "--eps", "1500",  "--cam",  "az=30,el=20"};
        rawArgs.insert(rawArgs.end(), RAW_ARGS.begin(), RAW_ARGS.end());
        const CliResult r = runVots(rawArgs);
        ASSERT_EQ(r.exitCode, 0) << describe(rawArgs, r);
        const std::vector<std::string> nrrdArgs{"render", head.nhdr, "-o",     fromNrrd,
                                                "--size", "64x48",   "--mode", mode,
                                                "--eps",  "1500",    "--cam",  "az=30,el=20"};
        const CliResult n = runVots(nrrdArgs);
        ASSERT_EQ(n.exitCode, 0) << describe(nrrdArgs, n);
        const std::string png = fileBytes(fromRaw);
        ASSERT_GT(png.size(), 8u) << mode;
        EXPECT_EQ(png, fileBytes(fromNrrd)) << mode;
    }
}

TEST(CliRenderRaw, ARawInputNeedsItsTypeAndDims) {
    RawHead head;
    const std::string out = head.dir.file("out.png");
    const std::vector<std::string> args{"render", head.raw, "-o", out, "--raw-dims", "33,41,25"};
    const CliResult r = runVots(args);
    EXPECT_EQ(r.exitCode, 2) << describe(args, r);
    EXPECT_NE(r.err.find("--raw-type"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CliRenderRaw, RawOptionsWithoutAVolumeForAVotsInputAreRefused) {
    RawHead head;
    const std::string vots = head.dir.file("head.vots");
    std::vector<std::string> fitArgs{"fit", head.raw, "-o", vots, "--eps", "1500"};
    fitArgs.insert(fitArgs.end(), RAW_ARGS.begin(), RAW_ARGS.end());
    ASSERT_EQ(runVots(fitArgs).exitCode, 0);
    const std::string out = head.dir.file("out.png");
    std::vector<std::string> args{"render", vots, "-o", out};
    args.insert(args.end(), RAW_ARGS.begin(), RAW_ARGS.end());
    const CliResult r = runVots(args);
    EXPECT_EQ(r.exitCode, 2) << describe(args, r);
    EXPECT_NE(r.err.find("--volume"), std::string::npos) << r.err;
    // With the volume named, the layout applies to it and a reference frame renders.
    args.insert(args.end(), {"--volume", head.raw, "--mode", "reference"});
    const CliResult withVolume = runVots(args);
    EXPECT_EQ(withVolume.exitCode, 0) << describe(args, withVolume);
}

} // namespace
} // namespace vots::test
