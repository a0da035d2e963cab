// 4D files and NaN samples through the real `vots` binary: --frame on fit, render and verify, the note
// without it, the frame errors, and no-data samples reported by `vots info`.
#include "CliExpect.h"
#include "CliRunner.h"
#include "TempDir.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

namespace vots::test {
namespace {

const std::string NIBABEL_DATA = "/usr/lib/python3/dist-packages/nibabel/tests/data/";
const std::string FUNCTIONAL = NIBABEL_DATA + "functional.nii"; // 17 x 21 x 3, 20 frames

TEST(CliFrames, WithoutFrameTheFirstIsReadAndStderrSaysHowMany) {
    TempDir dir;
    const std::vector<std::string> args{"fit", FUNCTIONAL, "-o", dir.file("f.vots"), "--eps", "2%"};
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << describe(args, r);
    EXPECT_NE(r.err.find("holds 20 frames; reading frame 0 (choose one with --frame N)"), std::string::npos)
        << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.file("f.vots")));
}

TEST(CliFrames, TheChosenFrameIsFittedVerifiedRenderedAndRecorded) {
    TempDir dir;
    const std::string out = dir.file("f7.vots");
    CliResult r = runVots({"fit", FUNCTIONAL, "-o", out, "--eps", "2%", "--frame", "7"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("reading frame 0"), std::string::npos) << r.err;
    r = runVots({"info", out});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("frame       7 (of a 4D file)"), std::string::npos) << r.out;
    r = runVots({"verify", out, FUNCTIONAL, "--frame", "7"});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    // Another frame's samples are not the ones fitted: verify says so.
    r = runVots({"verify", out, FUNCTIONAL, "--frame", "8"});
    EXPECT_NE(r.exitCode, 0) << r.out;
    r = runVots(
        {"render", NIBABEL_DATA + "test.mgz", "--frame", "1", "--eps", "1%", "-o", dir.file("m.png")});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.file("m.png")));
}

TEST(CliFrames, AFrameTheFileDoesNotHoldIsBadInput) {
    TempDir dir;
    expectBadInput(dir, {"fit", FUNCTIONAL, "-o", dir.file("o.vots"), "--eps", "2%", "--frame", "20"},
                   "has no frame 20: it holds 20 frames (0 to 19)");
    expectBadInput(dir, {"fit", FUNCTIONAL, "-o", dir.file("o.vots"), "--eps", "2%", "--frame=-1"},
                   "has no frame -1");
    expectBadInput(
        dir,
        {"fit", NIBABEL_DATA + "anatomical.nii", "-o", dir.file("o.vots"), "--eps", "2%", "--frame", "1"},
        "it holds 1 frame (0)");
    expectBadInput(dir,
                   {"render", NIBABEL_DATA + "example4d.nii.gz", "-o", dir.file("o.png"), "--frame", "2"},
                   "has no frame 2: it holds 2 frames");
}

TEST(CliFrames, NanSamplesAreNoDataAndAllNanIsBadInput) {
    TempDir dir;
    const std::string out = dir.file("r.vots");
    const std::string resampled = NIBABEL_DATA + "resampled_anat_moved.nii"; // 153 NaN of 1071
    CliResult r = runVots({"fit", resampled, "-o", out, "--eps", "2%"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runVots({"info", out});
    EXPECT_NE(r.out.find("153 samples NaN or Inf"), std::string::npos) << r.out;
    r = runVots({"verify", out, resampled});
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;

    std::string nrrd = "NRRD0004\ntype: float\ndimension: 3\nsizes: 4 4 4\nencoding: raw\nendian: little\n\n";
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int i = 0; i < 64; ++i)
        nrrd.append(reinterpret_cast<const char*>(&nan), sizeof nan);
    const std::string allNan = dir.file("nan.nrrd");
    std::ofstream(allNan, std::ios::binary) << nrrd;
    expectBadInput(dir, {"fit", allNan, "-o", dir.file("n.vots"), "--eps", "1"},
                   "all 64 samples are NaN or Inf");
}

} // namespace
} // namespace vots::test

namespace vots::test {
namespace {

// `--frames all`: one image per frame at one camera; with a fixed window each is the image of that
// frame alone.
TEST(CliFrames, FramesAllDrawsEveryFrameAsEachAlone) {
    TempDir dir;
    const std::string pattern = dir.file("%03d.png");
    const std::vector<std::string> common{"--renderer", "grid", "--window", "5300,600", "--size", "48x40"};
    std::vector<std::string> args{"render", FUNCTIONAL, "--frames", "all", "-o", pattern};
    args.insert(args.end(), common.begin(), common.end());
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << describe(args, r);
    for (int frame = 0; frame < 20; ++frame) {
        char name[16];
        std::snprintf(name, sizeof name, "%03d.png", frame);
        ASSERT_TRUE(std::filesystem::exists(dir.file(name))) << name;
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file("020.png")));
    for (const int frame : {0, 7, 19}) {
        const std::string alone = dir.file("alone.png");
        std::vector<std::string> one{"render", FUNCTIONAL, "--frame", std::to_string(frame), "-o", alone};
        one.insert(one.end(), common.begin(), common.end());
        ASSERT_EQ(runVots(one).exitCode, 0);
        char name[16];
        std::snprintf(name, sizeof name, "%03d.png", frame);
        EXPECT_EQ(slurpText(dir.file(name)), slurpText(alone)) << "frame " << frame;
    }
    EXPECT_NE(slurpText(dir.file("000.png")), slurpText(dir.file("019.png")));
    expectBadInput(dir, {"render", FUNCTIONAL, "--frames", "some", "-o", dir.file("%03d.x.png")},
                   "only 'all'");
    expectBadInput(dir,
                   {"render", FUNCTIONAL, "--frames", "all", "--frame", "1", "-o", dir.file("%03d.y.png")},
                   "not with --frame");
}

} // namespace
} // namespace vots::test
