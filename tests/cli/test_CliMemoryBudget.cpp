// `vots fit` and `vots render` under --memory-budget: a header announcing a huge volume is refused with
// one line and exit 2 before the samples are read, and nothing is written; a small volume within the
// budget is fitted as usual.
#include "CliRunner.h"
#include "TempDir.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <set>

namespace vots::test {
namespace {

namespace fs = std::filesystem;

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";

/// The names in a folder, to show nothing was added.
std::set<std::string> namesIn(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.insert(entry.path().filename().string());
    return names;
}

/// Headers of every format announcing 100000^3 (NIfTI: 32767^3) samples over a few bytes of data.
std::vector<std::string> writeHugeHeaders(const TempDir& dir) {
    dir.write("tiny.raw", std::string(16, '\0'));
    std::vector<std::string> paths;
    const std::string nrrd = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\nencoding: ";
    paths.push_back(dir.write("huge.nhdr", nrrd + "raw\ndata file: tiny.raw\n"));
    paths.push_back(dir.write("huge.nrrd", nrrd + "raw\n\n" + std::string(16, '\0')));
    paths.push_back(dir.write("gzip.nhdr", nrrd + "gzip\ndata file: tiny.raw\n"));
    paths.push_back(dir.write("huge.mha", "ObjectType = Image\nNDims = 3\nDimSize = 100000 100000 100000\n"
                                          "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n" +
                                              std::string(16, '\0')));
    std::string nifti(352, '\0');
    const auto put16 = [&](std::size_t at, std::uint16_t v) { std::memcpy(&nifti[at], &v, 2); };
    const std::int32_t sizeofHdr = 348;
    const float voxOffset = 352.f, pixdim = 1.f;
    std::memcpy(&nifti[0], &sizeofHdr, 4);
    put16(40, 3), put16(42, 32767), put16(44, 32767), put16(46, 32767), put16(70, 2), put16(72, 8);
    for (std::size_t a = 0; a < 4; ++a)
        std::memcpy(&nifti[76 + 4 * a], &pixdim, 4);
    std::memcpy(&nifti[108], &voxOffset, 4);
    nifti.replace(344, 4, std::string("n+1\0", 4));
    paths.push_back(dir.write("huge.nii", nifti + std::string(16, '\0')));
    return paths;
}

void expectBudgetRefusal(const std::vector<std::string>& args, const CliResult& r, const std::string& dims) {
    const std::string what = describe(args, r);
    EXPECT_EQ(r.exitCode, 2) << what;
    ASSERT_EQ(r.errLines().size(), 1u) << what;
    EXPECT_NE(r.err.find("memory budget"), std::string::npos) << what;
    EXPECT_NE(r.err.find(dims), std::string::npos) << what;
}

TEST(CliMemoryBudget, FitRefusesAHugeHeaderOfEveryFormatAndWritesNothing) {
    TempDir dir;
    for (const std::string& input : writeHugeHeaders(dir)) {
        const std::set<std::string> before = namesIn(dir.path());
        const std::string dims = input.ends_with(".nii") ? "32767x32767x32767" : "100000x100000x100000";
        for (const std::string& budget : {std::string(), std::string("64G")}) {
            std::vector<std::string> args{"fit", input, "-o", dir.file("out.vots"), "--eps", "5"};
            if (!budget.empty()) args.insert(args.end(), {"--memory-budget", budget});
            expectBudgetRefusal(args, runVots(args), dims);
            EXPECT_EQ(namesIn(dir.path()), before) << input; // no output, no temporary
        }
    }
}

TEST(CliMemoryBudget, RawLayoutIsCheckedToo) {
    TempDir dir;
    const std::string input = dir.write("tiny.raw", std::string(16, '\0'));
    const std::vector<std::string> args{"fit",        input,  "-o",         dir.file("out.vots"),
                                        "--eps",      "5",    "--raw-dims", "100000,100000,100000",
                                        "--raw-type", "int16"};
    expectBudgetRefusal(args, runVots(args), "100000x100000x100000 int16");
    EXPECT_FALSE(fs::exists(dir.file("out.vots")));
}

TEST(CliMemoryBudget, RenderOfAVolumeRefusesAHugeHeaderBeforeLoading) {
    TempDir dir;
    const std::string input = writeHugeHeaders(dir)[0];
    for (const char* mode : {"mip", "reference"}) {
        const std::vector<std::string> args{"render", input, "-o", dir.file("out.png"), "--mode", mode};
        expectBudgetRefusal(args, runVots(args), "100000x100000x100000");
        EXPECT_FALSE(fs::exists(dir.file("out.png")));
    }
}

TEST(CliMemoryBudget, ASmallVolumeFitsUnderASmallBudgetThatIsBigEnough) {
    TempDir dir;
    // The brain MRI is 34 k int16 samples: its estimate is the model's fixed part plus a fraction of a MB.
    // The budget also covers what the process holds before the load: ~20 MB, but ~150 MB under ASan.
    const std::vector<std::string> fits{"fit", MRI_BRAIN,         "-o",  dir.file("ok.vots"), "--eps",
                                        "5%",  "--memory-budget", "512M"};
    const CliResult ok = runVots(fits);
    EXPECT_EQ(ok.exitCode, 0) << describe(fits, ok);
    EXPECT_GT(fs::file_size(dir.file("ok.vots")), 100u);

    // The same volume under a budget below its estimate: refused, so the budget is really applied.
    const std::vector<std::string> tight{"fit", MRI_BRAIN,         "-o", dir.file("no.vots"), "--eps",
                                         "5%",  "--memory-budget", "64M"};
    expectBudgetRefusal(tight, runVots(tight), "33x41x25 int16");
    EXPECT_FALSE(fs::exists(dir.file("no.vots")));
}

TEST(CliMemoryBudget, AMalformedBudgetIsABadArgument) {
    TempDir dir;
    for (const char* bad : {"8X", "0", "lots"}) {
        const std::vector<std::string> args{"fit", MRI_BRAIN,         "-o", dir.file("x.vots"), "--eps",
                                            "5%",  "--memory-budget", bad};
        const CliResult r = runVots(args);
        EXPECT_EQ(r.exitCode, 2) << describe(args, r);
        EXPECT_NE(r.err.find("--memory-budget"), std::string::npos) << describe(args, r);
        EXPECT_FALSE(fs::exists(dir.file("x.vots")));
    }
}

} // namespace
} // namespace vots::test
