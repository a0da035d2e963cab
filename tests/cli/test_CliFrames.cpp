// 4D files and NaN samples through the real `vots` binary: --frame on fit, render and verify, the note
// without it, the frame errors, and no-data samples reported by `vots info`.
#include "CliExpect.h"
#include "CliRunner.h"
#include "NiftiFloat32.h"
#include "TempDir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <vector>

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

// --frame max: each sample the largest over the frames (a NaN where one frame has no data is passed over).
TEST(CliFrames, FrameMaxIsTheMaximumOverTheFramesAtEachSample) {
    TempDir dir;
    const std::array<int, 3> dims{12, 10, 8};
    std::vector<float> frames, most;
    for (int t = 0; t < 3; ++t)
        for (int z = 0; z < dims[2]; ++z)
            for (int y = 0; y < dims[1]; ++y)
                for (int x = 0; x < dims[0]; ++x) {
                    // Each frame is brightest in another third of the x axis.
                    const float value = (x / 4 == t ? 500.f : 100.f) + static_cast<float>(y + z);
                    frames.push_back(x == 5 && y == 5 && z == 4 && t == 1
                                         ? std::numeric_limits<float>::quiet_NaN()
                                         : value);
                }
    const std::size_t n = frames.size() / 3;
    for (std::size_t i = 0; i < n; ++i)
        most.push_back(std::max(
            {frames[i], frames[n + i] == frames[n + i] ? frames[n + i] : frames[i], frames[2 * n + i]}));
    const std::string four = dir.write("four.nii", niftiFloat32(dims, 3, frames));
    const std::string expected = dir.write("max.nii", niftiFloat32(dims, 1, most));
    const std::string out = dir.file("max.vots");
    CliResult r = runVots({"fit", four, "--frame", "max", "-o", out, "--eps", "1"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(runVots({"verify", out, expected}).exitCode, 0);
    EXPECT_EQ(runVots({"verify", out, four, "--frame", "max"}).exitCode, 0);
    for (const char* frame : {"0", "1", "2"})
        EXPECT_NE(runVots({"verify", out, four, "--frame", frame}).exitCode, 0) << frame;
    r = runVots({"info", out});
    EXPECT_NE(r.out.find("max (the maximum over the frames of a 4D file)"), std::string::npos) << r.out;
    // The grid draws the maximum's samples: the PNG of the 3D file of the maxima.
    r = runVots({"render", four, "--frame", "max", "--mode", "reference", "--size", "48x40", "-o",
                 dir.file("a.png")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runVots({"render", expected, "--mode", "reference", "--size", "48x40", "-o", dir.file("b.png")});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream a(dir.file("a.png"), std::ios::binary), b(dir.file("b.png"), std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(a), {}),
              std::string(std::istreambuf_iterator<char>(b), {}));
    expectBadInput(dir, {"fit", four, "--frame", "maximum", "-o", dir.file("no.vots")},
                   "not a frame number or 'max'");
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
