// `vots render --turntable N`: PNG frames equal single renders byte for byte, the WebM decodes, bad input
// exits 2, a missing encoder module exits 1.
#include "CliExpect.h"
#include "CliRunner.h"
#include "TempDir.h"
#include "WebmProbe.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace vots::test {
namespace {

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";
constexpr int FRAMES = 5;

std::string shortest(double value) {
    char text[64];
    const auto end = std::to_chars(text, text + sizeof text, value).ptr;
    return std::string(text, end);
}

/// The camera the brief promises for frame k of a turn from az=300 at el 15: azimuth 300 + k * 72,
/// less 360 above 360.
std::string frameCamera(int k) {
    double azimuth = 300.0 + k * (360.0 / FRAMES);
    if (azimuth > 360.0) azimuth -= 360.0;
    return "az=" + shortest(azimuth) + ",el=15";
}

TEST(CliTurntable, PngFramesEqualSingleRendersAndRepeatByteForByte) {
    TempDir dir;
    std::filesystem::create_directories(dir.path() / "a");
    std::filesystem::create_directories(dir.path() / "b");
    const std::vector<std::string> turn = {
        "render",       MRI_BRAIN,     "--size", "64x48",       "--cam",
        "az=300,el=40", "--elevation", "15",     "--turntable", std::to_string(FRAMES)};
    std::vector<std::string> first = turn;
    first.insert(first.end(), {"-o", dir.file("a/%03d.png")});
    const CliResult r = runVots(first);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path() / "a"), {}), FRAMES)
        << "exactly the frames, no temporaries";
    std::vector<std::string> again = turn;
    again.insert(again.end(), {"-o", dir.file("b/turn-%d.png")});
    ASSERT_EQ(runVots(again).exitCode, 0);

    std::string previous;
    for (int k = 0; k < FRAMES; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "a/%03d.png", k);
        const std::string frame = slurpText(dir.file(name));
        ASSERT_FALSE(frame.empty()) << name;
        const std::string single = dir.file("single-" + std::to_string(k) + ".png");
        const CliResult one =
            runVots({"render", MRI_BRAIN, "--size", "64x48", "--cam", frameCamera(k), "-o", single});
        ASSERT_EQ(one.exitCode, 0) << one.err;
        EXPECT_EQ(frame, slurpText(single)) << "frame " << k << " differs from --cam " << frameCamera(k);
        EXPECT_EQ(frame, slurpText(dir.file("b/turn-" + std::to_string(k) + ".png")))
            << "rerun of frame " << k;
        EXPECT_NE(frame, previous) << "frame " << k << " repeats the one before: the camera did not turn";
        previous = frame;
    }
}

TEST(CliTurntable, WebmDecodesToTheFramesAndRepeatsByteForByte) {
    TempDir dir;
    std::vector<std::string> args = {"render",      MRI_BRAIN,     "--size", "64x48", "--cam",
                                     "az=30,el=20", "--turntable", "7",      "-o",    dir.file("turn.webm")};
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const std::string& line : r.errLines()) // FFmpeg's own log lines must not reach stderr
        EXPECT_EQ(line.rfind("vots: ", 0), 0u) << line;
    const VideoProbe probe = probeVideo(dir.file("turn.webm"));
    ASSERT_TRUE(probe.opened);
    EXPECT_EQ(probe.error, "");
    EXPECT_NE(probe.container.find("webm"), std::string::npos) << probe.container;
    EXPECT_EQ(probe.codec, "vp9");
    EXPECT_EQ(probe.framesDecoded, 7);
    EXPECT_EQ(probe.width, 64);
    EXPECT_EQ(probe.height, 48);
    args.back() = dir.file("again.WEBM");
    ASSERT_EQ(runVots(args).exitCode, 0);
    EXPECT_EQ(slurpText(dir.file("turn.webm")), slurpText(dir.file("again.WEBM")));
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 2) << "no temporaries";
}

/// Points the children's module lookup at `path` (WebmModuleLoader.h) while it lives.
struct ModuleOverride {
    explicit ModuleOverride(const std::string& path) { ::setenv("VOTS_WEBM_MODULE", path.c_str(), 1); }
    ~ModuleOverride() { ::unsetenv("VOTS_WEBM_MODULE"); }
    ModuleOverride(const ModuleOverride&) = delete;
    ModuleOverride& operator=(const ModuleOverride&) = delete;
};

TEST(CliTurntable, WithoutItsEncoderModuleAWebmFailsWithOneLineAndAPngStillRenders) {
    TempDir dir;
    const std::string missing = dir.file("no-such-folder/libvots_webm.so");
    const ModuleOverride module(missing);
    const CliResult r =
        runVots({"render", MRI_BRAIN, "--size", "32x32", "--turntable", "3", "-o", dir.file("t.webm")});
    const std::string error = "vots: error: WebM encoding needs the module libvots_webm.so";
    EXPECT_EQ(r.exitCode, 1) << r.err;
    ASSERT_FALSE(r.errLines().empty());
    EXPECT_EQ(r.errLines().back().rfind(error, 0), 0u) << "one line: " << r.err;
    EXPECT_NE(r.err.find(missing), std::string::npos) << "names the path it tried: " << r.err;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 0)
        << "no file, no temporary";
    // A PNG never loads the module, so the broken path does not matter to it.
    const CliResult png = runVots({"render", MRI_BRAIN, "--size", "32x32", "-o", dir.file("one.png")});
    EXPECT_EQ(png.exitCode, 0) << png.err;
}

TEST(CliTurntable, BadArgumentsExit2WithOneLine) {
    TempDir dir;
    const std::string frames = dir.file("%03d.png");
    const auto bad = [&](std::vector<std::string> extra, const std::string& needle) {
        std::vector<std::string> args = {"render", MRI_BRAIN, "--size", "32x32"};
        args.insert(args.end(), extra.begin(), extra.end());
        expectBadInput(dir, args, needle);
    };
    bad({"--turntable", "0", "-o", frames}, "--turntable 0 is outside 1..3600");
    bad({"--turntable", "100000", "-o", frames}, "--turntable 100000 is outside 1..3600");
    bad({"--turntable", "-3", "-o", frames}, "outside 1..3600");
    bad({"--turntable", "many", "-o", frames}, "--turntable");
    bad({"--turntable", "4", "-o", dir.file("frames.png")}, "one %d or %0Nd");
    bad({"--turntable", "4", "-o", dir.file("%d-%d.png")}, "one %d or %0Nd");
    bad({"--turntable", "4", "-o", dir.file("%s.png")}, "one %d or %0Nd");
    bad({"--turntable", "4", "-o", dir.file("no-such-folder/%03d.png")}, "does not exist");
    bad({"--turntable", "4", "-o", dir.file("no-such-folder/turn.webm")}, "does not exist");
    bad({"--turntable", "4", "--elevation", "95", "-o", frames}, "el");
    bad({"--elevation", "10", "-o", dir.file("one.png")}, "--elevation is for --turntable N");
    bad({"-o", dir.file("one.webm")}, "needs --turntable N");
    expectBadInput(dir, {"render", MRI_BRAIN, "--size", "1x32", "--turntable", "4", "-o", dir.file("t.webm")},
                   "too small for a WebM");
}

} // namespace
} // namespace vots::test
