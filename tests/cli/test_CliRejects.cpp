// Bad input through the real `vots` binary: exit 2, one "vots: error:" line, and no output file.
#include "CliExpect.h"
#include "CliRunner.h"
#include "TempDir.h"
#include "VotSpaceBytes.h"

#include "vots/fit/VotSpaceFile.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace vots::test {
namespace {

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";

std::vector<std::string> fitWith(const std::string& out, std::vector<std::string> extra,
                                 const std::string& input = MRI_BRAIN) {
    std::vector<std::string> args{"fit", input, "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

TEST(CliRejects, BadFitArguments) {
    TempDir dir;
    const std::string out = dir.file("out.vots");
    expectBadInput(dir, fitWith(out, {"--eps", "2"}, dir.file("missing.nrrd")), "missing.nrrd");
    expectBadInput(dir, fitWith(out, {"--eps", "0"}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps", "0%"}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps=-1"}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps", "-1"}), "eps");
    expectBadInput(dir, fitWith(out, {"--eps", "nan"}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps", "inf"}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps", "2x"}), "--eps");
    expectBadInput(dir, fitWith(out, {}), "--eps");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--degree", "4"}), "degree 4");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--degree=-1"}), "degree");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--focus", "10,10,10,5"}), "--eps-focus");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--eps-focus", "1"}), "--focus");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--focus", "10,10,10,0", "--eps-focus", "1"}), "radius");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--focus", "10,10,5", "--eps-focus", "1"}), "--focus");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--focus", "1,2,3,4", "--eps-focus", "nan"}),
                   "--eps-focus");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--method", "slow"}), "--method");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--certify", "pixels"}), "--certify");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--fit-norm", "l2"}), "--fit-norm");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--background", "dark"}), "--background");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--raw-dims", "4,4,4"}), "--raw-type");
    expectBadInput(dir, fitWith(out, {"--eps", "2", "--raw-dims", "4,4", "--raw-type", "uint8"}),
                   "--raw-dims");
    expectBadInput(dir, fitWith(dir.file("no/such/folder/out.vots"), {"--eps", "2"}), "no/such/folder");
}

TEST(CliRejects, ArgumentsAreCheckedBeforeTheInputIsRead) {
    TempDir dir;
    // The input does not exist, yet the message is about eps: arguments come first.
    expectBadInput(dir, fitWith(dir.file("out.vots"), {"--eps", "0"}, dir.file("missing.nrrd")), "--eps");
    expectBadInput(dir,
                   fitWith(dir.file("out.vots"), {"--eps", "2", "--degree", "4"}, dir.file("missing.nrrd")),
                   "degree 4");
}

TEST(CliRejects, BadProjectionArguments) {
    TempDir dir;
    const auto render = [&](std::vector<std::string> extra) {
        std::vector<std::string> args{"render", MRI_BRAIN, "-o", dir.file("out.png")};
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    expectBadInput(dir, render({"--mode", "xray"}), "unknown mode 'xray'");
    expectBadInput(dir, render({"--renderer", "gpu"}), "unknown renderer 'gpu'");
    expectBadInput(dir, render({"--mode", "reference", "--renderer", "vots"}), "reference");
    expectBadInput(dir, render({"--mode", "density", "--renderer", "grid"}), "density");
    for (const char* slab : {"5", "0,0", "1,-3", "nan,4", "1,2,3"})
        expectBadInput(dir, render({"--slab", slab}), "slab");
    expectBadInput(dir, render({"--mode", "density", "--slab", "0,10"}), "no slab");
}

TEST(CliRejects, BrokenVotsFiles) {
    TempDir dir;
    const Bytes good = fit::encodeVotSpace(makeSampleSpace(3));
    const std::string truncated = dir.write(
        "truncated.vots", std::string(good.begin(), good.begin() + static_cast<long>(good.size() / 2)));
    Bytes flipped = good;
    flipped[200] ^= 0x04;
    const std::string corrupt = dir.write("corrupt.vots", std::string(flipped.begin(), flipped.end()));
    const std::string notVots = dir.write("text.vots", "hello\n");

    expectBadInput(dir, {"info", truncated}, "truncated.vots");
    expectBadInput(dir, {"info", truncated, "--json"}, "does not match");
    expectBadInput(dir, {"info", corrupt}, "checksum");
    expectBadInput(dir, {"info", notVots}, "not a Vot-Space file");
    expectBadInput(dir, {"info", dir.file("missing.vots")}, "missing.vots");
    expectBadInput(dir, {"verify", truncated, MRI_BRAIN}, "truncated.vots");
    expectBadInput(dir, {"verify", corrupt, MRI_BRAIN}, "checksum");
    expectBadInput(dir, {"verify", dir.file("missing.vots"), MRI_BRAIN}, "missing.vots");
}

TEST(CliRejects, BadUsage) {
    TempDir dir;
    expectBadInput(dir, {}, "subcommand");
    expectBadInput(dir, {"frobnicate"}, "frobnicate");
    expectBadInput(dir, {"info"}, "FILE");
    expectBadInput(dir, {"verify", dir.file("a.vots")}, "INPUT");
    expectBadInput(dir, {"fit", MRI_BRAIN, "--eps", "2"}, "--output");
}

} // namespace
} // namespace vots::test
