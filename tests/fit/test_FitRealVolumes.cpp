// Both generators on the test volumes (scripts/make-test-volumes): full cover of foreground cells and verify
// passes.
#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"
#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace vots::fit;

namespace {

Volume loadShared(const std::string& name) {
    return loadVolume(std::string(VOTS_TEST_DATA_DIR) + "/" + name);
}

/// A sub-block of a real volume: the paper's seed-every-cell method is too slow for a quick test on
/// whole volumes, so it runs on a 24^3 block from the volume's busiest region.
Volume crop(const Volume& v, const std::array<int, 3>& lo, int side) {
    Volume out;
    out.name = v.name + "-crop";
    out.spacing = v.spacing;
    for (int a = 0; a < 3; ++a)
        out.dims[a] = std::min(side, v.dims[a] - lo[a]);
    out.values.resize(out.sampleCount());
    for (int z = 0; z < out.dims[2]; ++z)
        for (int y = 0; y < out.dims[1]; ++y)
            for (int x = 0; x < out.dims[0]; ++x)
                out.values[out.indexOf(x, y, z)] = v.at(lo[0] + x, lo[1] + y, lo[2] + z);
    return out;
}

struct Case {
    const char* file;
    float epsPercent;
};

class RealVolume : public ::testing::TestWithParam<Case> {};

void expectValidFit(const Volume& volume, FitMethod method, float epsPercent, int degree) {
    const auto r = volume.valueRange();
    FitOptions o;
    o.eps = epsPercent / 100.f * (r[1] - r[0]);
    o.degree = degree;
    o.method = method;
    o.background = defaultBackground(volume);
    const FitResult fit = fitVotSpace(volume, o);
    const VerifyReport report = verifyVotSpace(fit.space, volume);
    EXPECT_TRUE(report.ok) << volume.name << ": " << report.firstProblem;
    EXPECT_EQ(report.uncoveredCells, 0u) << volume.name;
    EXPECT_EQ(report.violations, 0u) << volume.name;
    EXPECT_LE(report.maxError, o.eps * (1.0 + 1e-5)) << volume.name;
    EXPECT_GT(report.nonBackgroundCells, 0u) << volume.name;
    EXPECT_LT(fit.space.vots.size(), report.nonBackgroundCells) << volume.name << ": Vots must merge cells";
    EXPECT_EQ(fit.stats.coveredCells, report.nonBackgroundCells)
        << "fitter and verifier disagree on background";
}

} // namespace

TEST_P(RealVolume, FastMethodCoversWholeVolumeWithinEps) {
    const Volume volume = loadShared(GetParam().file);
    for (int degree : {1, 3})
        expectValidFit(volume, FitMethod::Fast, GetParam().epsPercent, degree);
}

TEST_P(RealVolume, PaperMethodCoversBlockWithinEps) {
    const Volume full = loadShared(GetParam().file);
    const Volume block =
        crop(full, {full.dims[0] / 2 - 12, full.dims[1] / 2 - 12, full.dims[2] / 2 - 12}, 24);
    expectValidFit(block, FitMethod::Paper, GetParam().epsPercent, 3);
    expectValidFit(block, FitMethod::Fast, GetParam().epsPercent, 3);
}

INSTANTIATE_TEST_SUITE_P(TestVolumes, RealVolume,
                         ::testing::Values(Case{"mri-brain_33x41x25_int16.nii", 2.f},
                                           Case{"blobs_64x64x64_uint8.nrrd", 2.f},
                                           Case{"cranium-quarter_64x64x108_int16.nrrd", 2.f},
                                           Case{"orbital_64x64x64_float32.nrrd", 1.f}),
                         [](const auto& testInfo) {
                             std::string name = testInfo.param.file;
                             name = name.substr(0, name.find('_'));
                             name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                             return name;
                         });

TEST(RealVolumeFull, PaperMethodCoversTheWholeBrainMri) {
    expectValidFit(loadShared("mri-brain_33x41x25_int16.nii"), FitMethod::Paper, 2.f, 3);
}
