// DICOM folders through the real `vots` binary: fit, verify and render a series; --series; bad series.
#include "CliExpect.h"
#include "CliRunner.h"
#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace vots::test {
namespace {

/// A bright ball in air, HU-like: something for the MIP to show.
fit::Volume ball() {
    return sampleVolume({24, 20, 16},
                        [](int x, int y, int z) {
                            const double r = std::hypot(x - 11.5, y - 9.5, (z - 7.5) * 1.5);
                            return r < 7 ? 900.0 - 20.0 * r : -1000.0;
                        },
                        {0.8, 0.8, 1.2});
}

TEST(CliDicom, FitVerifyAndRenderAFolder) {
    TempDir series, out;
    DicomWriteOptions o;
    o.syntax = "jpeg-ls";
    o.order = DicomFileOrder::Shuffled;
    o.storeSigned = false;
    o.intercept = -1024;
    o.bitsStored = 12;
    writeDicomSeries(ball(), series.file("ct"), o);
    const std::string vots = out.file("ct.vots");
    const CliResult fit = runVots({"fit", series.file("ct"), "-o", vots, "--eps", "20"});
    ASSERT_EQ(fit.exitCode, 0) << fit.err;
    EXPECT_TRUE(std::filesystem::exists(vots));
    const CliResult verify = runVots({"verify", vots, series.file("ct")});
    EXPECT_EQ(verify.exitCode, 0) << verify.out << verify.err;
    EXPECT_NE(verify.out.find("OK"), std::string::npos) << verify.out;
    const CliResult render = runVots({"render", vots, "-o", out.file("a.png"), "--size", "64x64"});
    EXPECT_EQ(render.exitCode, 0) << render.err;
    EXPECT_GT(std::filesystem::file_size(out.file("a.png")), 100u);
    const CliResult direct =
        runVots({"render", series.file("ct"), "-o", out.file("b.png"), "--size", "64x64", "--eps", "20"});
    EXPECT_EQ(direct.exitCode, 0) << direct.err;
    EXPECT_TRUE(std::filesystem::exists(out.file("b.png")));
}

TEST(CliDicom, SeveralSeriesAreListedUntilOneIsPicked) {
    TempDir series, out;
    DicomWriteOptions a;
    a.seriesUid = "1.2.3.9.1";
    a.description = "axial";
    a.filePrefix = "a";
    DicomWriteOptions b = a;
    b.seriesUid = "1.2.3.9.2";
    b.description = "thin";
    b.filePrefix = "b";
    writeDicomSeries(ball(), series.file("study"), a);
    writeDicomSeries(ball(), series.file("study"), b);
    const std::string vots = out.file("s.vots");
    expectBadInput(out, {"fit", series.file("study"), "-o", vots, "--eps", "20"},
                   "1.2.3.9.1 \"axial\" (16 slices); 1.2.3.9.2 \"thin\" (16 slices)");
    expectBadInput(out, {"render", series.file("study"), "-o", out.file("x.png")}, "--series");
    expectBadInput(out, {"fit", series.file("study"), "-o", vots, "--eps", "20", "--series", "4.5.6"},
                   "has no series 4.5.6");
    const CliResult fit =
        runVots({"fit", series.file("study"), "-o", vots, "--eps", "20", "--series", "1.2.3.9.2"});
    ASSERT_EQ(fit.exitCode, 0) << fit.err;
    const CliResult verify = runVots({"verify", vots, series.file("study"), "--series", "1.2.3.9.2"});
    EXPECT_EQ(verify.exitCode, 0) << verify.err;
    const CliResult render = runVots({"render", series.file("study"), "--series", "1.2.3.9.1", "-o",
                                      out.file("r.png"), "--size", "32x32"});
    EXPECT_EQ(render.exitCode, 0) << render.err;
}

TEST(CliDicom, BadSeriesExitTwoWithoutOutput) {
    TempDir series, out;
    DicomWriteOptions drop;
    drop.dropSlice = 5;
    writeDicomSeries(ball(), series.file("missing"), drop);
    DicomWriteOptions resize;
    resize.resizeSlice = 2;
    writeDicomSeries(ball(), series.file("sizes"), resize);
    DicomWriteOptions cut;
    cut.truncateSlice = 7;
    writeDicomSeries(ball(), series.file("cut"), cut);
    std::filesystem::create_directories(series.file("empty"));
    writeDicomSeries(ball(), series.file("damaged"), {});
    std::filesystem::resize_file(series.file("damaged/slice-0003.dcm"), 300); // GDCM aborts on it
    const std::vector<std::pair<std::string, std::string>> cases = {{"missing", "missing slice"},
                                                                    {"sizes", "mixed image sizes"},
                                                                    {"cut", "truncated"},
                                                                    {"empty", "holds no DICOM images"},
                                                                    {"damaged", "damaged DICOM file"}};
    for (const auto& [name, needle] : cases) {
        SCOPED_TRACE(name);
        expectBadInput(out, {"fit", series.file(name), "-o", out.file(name + ".vots"), "--eps", "20"},
                       needle);
        expectBadInput(out, {"render", series.file(name), "-o", out.file(name + ".png")}, needle);
    }
}

// Found by fuzz_dicom: an element length of gigabytes, after the pixel data or misread in the header,
// made GDCM's child allocate it (peaks of 3.6 and 4.2 GB). The child's address space ends that early.
TEST(CliDicom, ALengthOfGigabytesIsADamagedFileWithinASmallPeak) {
    TempDir out;
    for (const char* name : {"huge-length-after-pixel-data", "huge-length-in-header"}) {
        SCOPED_TRACE(name);
        TempDir series;
        std::filesystem::copy_file(std::filesystem::path(VOTS_SOURCE_DIR) /
                                       "tests/fuzz/regressions/fuzz_dicom" / name,
                                   series.file("slice-0001.dcm"));
        const std::vector<std::string> args = {
            "fit", series.path().string(), "-o", out.file("x.vots"), "--eps", "10"};
        const CliResult r = runVots(args);
        EXPECT_EQ(r.exitCode, 2) << describe(args, r);
        ASSERT_EQ(r.errLines().size(), 1u) << describe(args, r);
        EXPECT_NE(r.err.find("slice-0001.dcm: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("damaged"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out.file("x.vots")));
        EXPECT_LT(r.peakResidentKb, 500 * 1024) << "peak of vots and its DICOM reader";
    }
}

} // namespace
} // namespace vots::test
