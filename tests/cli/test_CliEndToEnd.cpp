// End to end through the real `vots` binary on a real MRI volume: fit -> info --json -> verify.
#include "CliRunner.h"
#include "Int16Bytes.h"
#include "TempDir.h"
#include "VotSpaceBytes.h"

#include "vots/fit/Verify.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>

namespace vots::test {
namespace {

using nlohmann::json;

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";
const std::string BLOBS = std::string(VOTS_TEST_DATA_DIR) + "/blobs_64x64x64_uint8.nrrd";

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

/// One fit of the brain MRI shared by the suite (the fit is the slow part).
class CliEndToEnd : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sDir = std::make_unique<TempDir>();
        sVots = sDir->file("head.vots");
        sFitArgs = {"fit", MRI_BRAIN, "-o", sVots, "--eps", "3%", "--degree", "2", "--threads", "2"};
        sFit = runVots(sFitArgs);
    }
    static void TearDownTestSuite() { sDir.reset(); }

    static json infoJson(const std::string& file) {
        const CliResult r = runVots({"info", file, "--json"});
        EXPECT_EQ(r.exitCode, 0) << r.err;
        return json::parse(r.out);
    }

    static inline std::unique_ptr<TempDir> sDir;
    static inline std::string sVots;
    static inline std::vector<std::string> sFitArgs;
    static inline CliResult sFit;
};

TEST_F(CliEndToEnd, FitWritesTheFileAndASummary) {
    ASSERT_EQ(sFit.exitCode, 0) << describe(sFitArgs, sFit);
    EXPECT_TRUE(std::filesystem::is_regular_file(sVots));
    EXPECT_NE(sFit.out.find("Vots"), std::string::npos) << sFit.out;
    EXPECT_NE(sFit.out.find("max error"), std::string::npos) << sFit.out;
    EXPECT_EQ(sFit.err, "");
    // Only the result is left in the folder: no temp files.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(sDir->path()), {}), 1);
}

TEST_F(CliEndToEnd, InfoJsonDescribesTheFit) {
    ASSERT_EQ(sFit.exitCode, 0) << describe(sFitArgs, sFit);
    const json j = infoJson(sVots);
    EXPECT_EQ(j.at("dims"), json({33, 41, 25}));
    EXPECT_EQ(j.at("spacing"), json({2.0, 2.0, 2.0}));
    EXPECT_EQ(j.at("requested_degree"), 2);
    EXPECT_GE(j.at("degree").get<int>(), 2); // cell Vots may lift the header degree to 3 (docs/DESIGN.md §2)
    const double eps = j.at("eps").get<double>();
    EXPECT_NEAR(eps, 0.03 * (30393 + 610), 1e-3); // 3 % of the value range -610..30393
    const auto count = j.at("vot_count").get<std::size_t>();
    EXPECT_GT(count, 0u);
    EXPECT_NEAR(j.at("vots_per_sample").get<double>(), double(count) / (33.0 * 41 * 25), 1e-12);
    EXPECT_TRUE(j.at("vots_per_nonbackground_cell").is_number());
    std::size_t histogramTotal = 0;
    for (const json& bin : j.at("box_size_histogram"))
        histogramTotal += bin.at("count").get<std::size_t>();
    EXPECT_EQ(histogramTotal, count);
    EXPECT_LE(j.at("max_error").get<double>(), eps * (1 + 1e-6));
    EXPECT_TRUE(j.at("fit_seconds").is_number());
    EXPECT_EQ(j.at("meta").at("source").at("name"), "mri-brain_33x41x25_int16");
    EXPECT_EQ(j.at("meta").at("fit").at("eps_arg"), "3%");
    EXPECT_EQ(j.at("meta").at("fit").at("method"), "fast");
    EXPECT_TRUE(j.at("meta").at("max_error").is_number());
}

TEST_F(CliEndToEnd, InfoTextNamesEachField) {
    ASSERT_EQ(sFit.exitCode, 0);
    const CliResult r = runVots({"info", sVots});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* key : {"grid", "33 x 41 x 25", "degree", "2 requested", "eps", "(given as 3%)",
                            "background", "Vots", "per sample", "max error", "fit time", "box sizes", "33+",
                            "fast method, minimax norm, certified at samples\n"})
        EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing from:\n" << r.out;
}

TEST_F(CliEndToEnd, InfoNamesTheNormAndTheCertificationOfALeastSquaresFit) {
    // A least-squares fit's meta block names no norm (its bytes are those from before the norm could be
    // chosen): info still says which norm made it.
    const std::string out = sDir->file("lsq-cells.vots");
    const CliResult fit = runVots({"fit", MRI_BRAIN, "-o", out, "--eps", "3%", "--fit-norm", "lsq",
                                   "--certify", "cells", "--threads", "2"});
    ASSERT_EQ(fit.exitCode, 0) << fit.err;
    const CliResult r = runVots({"info", out});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("fast method, least-squares norm, certified at samples and cells\n"),
              std::string::npos)
        << r.out;
    const json j = infoJson(out);
    EXPECT_EQ(j.at("fit_norm"), "lsq");
    EXPECT_EQ(j.at("certify"), "cells");
    EXPECT_EQ(infoJson(sVots).at("fit_norm"), "minimax");
}

TEST_F(CliEndToEnd, TheFileCountsOmittedCellsAsTheirFillAsTheVolumeDoes) {
    // A CT, whose air the fit leaves out (the brain MRI has none below its threshold).
    const std::string ct = std::string(VOTS_TEST_DATA_DIR) + "/cranium-quarter_64x64x108_int16.nrrd";
    const std::string ctVots = sDir->file("ct.vots");
    const std::vector<std::string> fitArgs{"fit", ct,         "-o", ctVots,      "--eps",
                                           "3%",  "--degree", "2",  "--threads", "2"};
    const CliResult fitRun = runVots(fitArgs);
    ASSERT_EQ(fitRun.exitCode, 0) << describe(fitArgs, fitRun);
    const json info = infoJson(ctVots);
    ASSERT_TRUE(info.at("background_fill").is_number()) << info.dump();
    // The mean of the air the fit left out lies below the threshold it was left out by, and not below
    // the CT's least sample (-1024 HU).
    EXPECT_LT(info.at("background_fill").get<double>(), info.at("background").get<double>());
    EXPECT_GE(info.at("background_fill").get<double>(), -1024.0);

    // The same file without the key, as written before it: omitted cells count as the threshold.
    fit::VotSpace space = meta::readVotSpaceFile(ctVots);
    json meta = json::parse(space.metaJson);
    meta.erase("background_fill");
    space.metaJson = meta.dump();
    const std::string old = sDir->file("old.vots");
    fit::writeVotSpaceFile(old, space);
    EXPECT_TRUE(infoJson(old).at("background_fill").is_null());

    const auto render = [&](const std::string& input, const std::string& mode, const std::string& png,
                            bool fit) {
        std::vector<std::string> args{"render", input,   "-o",       sDir->file(png),
                                      "--mode", mode,    "--view",   "anterior",
                                      "--size", "64x64", "--window", "-500,1000"};
        if (fit) args.insert(args.end(), {"--eps", "3%", "--degree", "2", "--certify", "samples"});
        const CliResult r = runVots(args);
        EXPECT_EQ(r.exitCode, 0) << describe(args, r);
        return readBytes(sDir->file(png));
    };
    for (const std::string mode : {"minip", "aip"}) {
        const auto fromFile = render(ctVots, mode, "file.png", false);
        EXPECT_EQ(fromFile, render(ct, mode, "volume.png", true)) << mode;
        EXPECT_NE(fromFile, render(old, mode, "old.png", false)) << mode << ": the fill changes the air";
    }
    EXPECT_EQ(render(ctVots, "mip", "file.png", false), render(old, "mip", "old.png", false))
        << "the max ignores omitted cells";
    for (const std::string& file : {ctVots, old})
        std::filesystem::remove(file);
    for (const char* png : {"file.png", "volume.png", "old.png"})
        std::filesystem::remove(sDir->file(png));
}

TEST_F(CliEndToEnd, VerifyPassesOnTheFit) {
    ASSERT_EQ(sFit.exitCode, 0);
    const CliResult r = runVots({"verify", sVots, MRI_BRAIN});
    EXPECT_EQ(r.exitCode, 0) << describe({"verify", sVots, MRI_BRAIN}, r);
    EXPECT_NE(r.out.find("result"), std::string::npos);
    EXPECT_NE(r.out.find("OK"), std::string::npos);
    EXPECT_NE(r.out.find("max cell-centre error"), std::string::npos);
    EXPECT_EQ(r.err, "");
}

TEST_F(CliEndToEnd, VerifyFailsOnATamperedVot) {
    ASSERT_EQ(sFit.exitCode, 0);
    fit::VotSpace space = meta::readVotSpaceFile(sVots);
    ASSERT_FALSE(space.vots.empty());
    space.vots[space.vots.size() / 2].c[0] += 10 * space.eps; // a valid file that is wrong
    const std::string bad = sDir->file("tampered.vots");
    fit::writeVotSpaceFile(bad, space);
    const CliResult r = runVots({"verify", bad, MRI_BRAIN});
    EXPECT_EQ(r.exitCode, 1) << describe({"verify", bad, MRI_BRAIN}, r);
    EXPECT_NE(r.out.find("FAILED"), std::string::npos) << r.out;
    ASSERT_EQ(r.errLines().size(), 1u) << r.err;
    EXPECT_EQ(r.errLines()[0].rfind("vots: verify failed", 0), 0u) << r.err;
    std::filesystem::remove(bad);
}

TEST_F(CliEndToEnd, VerifyAgainstAnotherVolumeIsBadInput) {
    ASSERT_EQ(sFit.exitCode, 0);
    const CliResult r = runVots({"verify", sVots, BLOBS});
    EXPECT_EQ(r.exitCode, 2) << describe({"verify", sVots, BLOBS}, r);
    EXPECT_EQ(r.errLines().size(), 1u) << r.err;
}

TEST(CliFit, RawInputWithFocusAndCellCertificationVerifies) {
    // The same MRI as headerless raw bytes, fitted with every option that changes the bound.
    const fit::Volume volume = fit::loadVolume(MRI_BRAIN);
    TempDir dir;
    const std::string raw = // behind a 16-byte junk header
        dir.write("brain.raw", std::string(16, 'h') + littleEndianInt16Bytes(volume));
    const std::string out = dir.file("focus.vots");
    const std::vector<std::string> rawArgs{"--raw-dims",    "33,41,25", "--raw-type",         "int16",
                                           "--raw-spacing", "2,2,2",    "--raw-header-bytes", "16"};
    std::vector<std::string> fitArgs{"fit",         raw,   "-o",           out,     "--eps",   "1500",
                                     "--degree",    "1",   "--certify",    "cells", "--focus", "16,20,12,8",
                                     "--eps-focus", "250", "--background", "none"};
    fitArgs.insert(fitArgs.end(), rawArgs.begin(), rawArgs.end());
    const CliResult fitRun = runVots(fitArgs);
    ASSERT_EQ(fitRun.exitCode, 0) << describe(fitArgs, fitRun);

    const fit::VotSpace space = meta::readVotSpaceFile(out);
    EXPECT_TRUE(space.epsVaries);
    EXPECT_EQ(space.spacing, (std::array<double, 3>{2, 2, 2}));
    const json meta = json::parse(space.metaJson);
    EXPECT_EQ(meta.at("fit").at("focus").at("radius"), 8.0);
    EXPECT_EQ(meta.at("fit").at("certify"), "cells");
    EXPECT_TRUE(meta.at("fit").at("background").is_null());

    std::vector<std::string> verifyArgs{"verify", out, raw};
    verifyArgs.insert(verifyArgs.end(), rawArgs.begin(), rawArgs.end());
    const CliResult verifyRun = runVots(verifyArgs);
    EXPECT_EQ(verifyRun.exitCode, 0) << describe(verifyArgs, verifyRun);
}

TEST(CliFit, FitNormChoosesHowBoxesAreAcceptedAndMinimaxNamesItInTheMeta) {
    TempDir dir;
    std::map<std::string, std::size_t> vots;
    for (const std::string norm : {"lsq", "minimax"}) {
        const std::string out = dir.file(norm + ".vots");
        const std::vector<std::string> args{"fit", MRI_BRAIN, "-o", out, "--eps", "3%", "--fit-norm", norm};
        const CliResult r = runVots(args);
        ASSERT_EQ(r.exitCode, 0) << describe(args, r);
        const fit::VotSpace space = meta::readVotSpaceFile(out);
        vots[norm] = space.vots.size();
        const json meta = json::parse(space.metaJson);
        // A least-squares file keeps the meta it had before the norm could be chosen.
        EXPECT_EQ(meta.at("fit").contains("norm"), norm == "minimax");
        if (norm == "minimax") {
            EXPECT_EQ(meta.at("fit").at("norm"), "minimax");
            EXPECT_GT(meta.at("stats").at("minimax_fits").get<std::size_t>(), 0u);
        }
        const std::vector<std::string> verify{"verify", out, MRI_BRAIN};
        const CliResult v = runVots(verify);
        EXPECT_EQ(v.exitCode, 0) << describe(verify, v);
    }
    EXPECT_LT(vots["minimax"], vots["lsq"]);
}

TEST(CliFit, ProgressGoesToStderrOnly) {
    TempDir dir;
    const std::string out = dir.file("p.vots");
    const std::vector<std::string> args{"fit", MRI_BRAIN, "-o", out, "--eps", "10%", "--progress"};
    const CliResult r = runVots(args);
    ASSERT_EQ(r.exitCode, 0) << describe(args, r);
    EXPECT_NE(r.err.find("fit:"), std::string::npos) << r.err; // not a terminal: plain lines
    EXPECT_EQ(r.err.find('\r'), std::string::npos);
    EXPECT_EQ(r.out.find("fit:"), std::string::npos);
}

TEST(CliHelp, EveryCommandHasHelp) {
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"--help"}, {"fit", "--help"}, {"info", "--help"}, {"verify", "--help"}}) {
        const CliResult r = runVots(args);
        EXPECT_EQ(r.exitCode, 0) << describe(args, r);
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << describe(args, r);
    }
    const CliResult v = runVots({"--version"});
    EXPECT_EQ(v.exitCode, 0);
    EXPECT_FALSE(v.out.empty());
}

} // namespace
} // namespace vots::test
