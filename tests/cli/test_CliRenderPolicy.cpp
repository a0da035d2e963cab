// `vots render` applies VOTS_WALK_SHADER: the same image for either walk stage, one warning for nonsense.
#include "CliRunner.h"
#include "TempDir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

namespace vots::test {
namespace {

const std::string MRI_BRAIN = std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii";
const std::string WARNING =
    "vots: warning: VOTS_WALK_SHADER=sideways is neither fragment nor compute; choosing by renderer";

/// Renders the head with VOTS_WALK_SHADER set to `shader` (unset when empty); returns the run and PNG.
std::pair<CliResult, std::string> renderWith(const TempDir& dir, const std::string& shader) {
    const std::string png = dir.file("head-" + (shader.empty() ? std::string("default") : shader) + ".png");
    if (shader.empty())
        ::unsetenv("VOTS_WALK_SHADER");
    else
        ::setenv("VOTS_WALK_SHADER", shader.c_str(), 1);
    const CliResult r = runVots({"render", MRI_BRAIN, "-o", png, "--size", "64x48", "--cam", "az=30,el=20"});
    ::unsetenv("VOTS_WALK_SHADER");
    return {r, slurpText(png)};
}

TEST(CliRenderPolicy, WalkShaderOverrideKeepsTheImageAndWarnsOnNonsense) {
    TempDir dir;
    const auto [plain, reference] = renderWith(dir, "");
    ASSERT_EQ(plain.exitCode, 0) << plain.err;
    ASSERT_FALSE(reference.empty());
    EXPECT_EQ(plain.err.find("VOTS_WALK_SHADER"), std::string::npos) << plain.err;
    for (const std::string shader : {"fragment", "compute"}) {
        const auto [run, png] = renderWith(dir, shader);
        EXPECT_EQ(run.exitCode, 0) << shader << ": " << run.err;
        EXPECT_EQ(png, reference) << "the " << shader << " walk drew another image";
    }
    const auto [nonsense, png] = renderWith(dir, "sideways");
    EXPECT_EQ(nonsense.exitCode, 0) << nonsense.err;
    EXPECT_EQ(png, reference);
    const std::vector<std::string> lines = nonsense.errLines();
    EXPECT_EQ(std::count(lines.begin(), lines.end(), WARNING), 1) << nonsense.err;
}

} // namespace
} // namespace vots::test
