// Generated volumes with known answers: NaN/Inf samples as no data in a fit, and frames of 4D NIfTI files.
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include "TempDir.h"
#include "VolumeFixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace vots::fit;
using vots::test::TempDir;

namespace {

constexpr float NAN_F = std::numeric_limits<float>::quiet_NaN();

// f = x + 2y + 3z on 12 x 10 x 8 points (a degree-1 field every box fits exactly), no data from x = 8 on
// and one +Inf at (2, 3, 4).
Volume linearWithNoData() {
    Volume v;
    v.dims = {12, 10, 8};
    v.values.resize(v.sampleCount());
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 12; ++x)
                v.values[v.indexOf(x, y, z)] = x >= 8 ? NAN_F : static_cast<float>(x + 2 * y + 3 * z);
    v.values[v.indexOf(2, 3, 4)] = std::numeric_limits<float>::infinity();
    return v;
}

} // namespace

TEST(NoData, CellsWithANonFiniteCornerAreLeftOutAndNoVotHoldsOne) {
    const Volume v = linearWithNoData();
    EXPECT_EQ(v.nonFiniteCount(), 4u * 10 * 8 + 1);
    EXPECT_EQ(v.valueRange()[0], 0.0f);
    EXPECT_EQ(v.valueRange()[1], 7.0f + 18.0f + 21.0f);
    FitOptions options;
    options.eps = 0.01f;
    options.degree = 1;
    const FitResult fit = fitVotSpace(v, options); // no threshold: only the no-data cells are left out
    // 11 x 9 x 7 cells; those with a corner at x >= 8 (cells x = 7..10) and the 8 around (2, 3, 4).
    constexpr std::size_t noData = 4 * 9 * 7 + 8;
    EXPECT_EQ(fit.stats.backgroundCells, noData);
    EXPECT_EQ(fit.stats.coveredCells, 11u * 9 * 7 - noData);
    for (const Vot& vot : fit.space.vots) {
        EXPECT_LE(vot.box.hi[0], 7);
        const bool holdsInf = vot.box.lo[0] <= 2 && vot.box.hi[0] >= 2 && vot.box.lo[1] <= 3 &&
                              vot.box.hi[1] >= 3 && vot.box.lo[2] <= 4 && vot.box.hi[2] >= 4;
        EXPECT_FALSE(holdsInf);
        EXPECT_LE(vot.err, 1e-3f);
    }
    const VerifyReport report = verifyVotSpace(fit.space, v, std::nullopt);
    EXPECT_TRUE(report.ok) << report.firstProblem;
    // The fill: every no-data cell counts as the lowest finite sample, 0.
    ASSERT_TRUE(fit.space.backgroundFill.has_value());
    EXPECT_EQ(*fit.space.backgroundFill, 0.0f);
}

TEST(NoData, AVolumeWithoutAFiniteSampleIsAClearError) {
    Volume v;
    v.dims = {4, 4, 4};
    v.values.assign(v.sampleCount(), NAN_F);
    v.values[5] = std::numeric_limits<float>::infinity();
    FitOptions options;
    try {
        fitVotSpace(v, options);
        FAIL() << "an all-NaN volume was fitted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("all 64 samples are NaN or Inf"), std::string::npos) << e.what();
    }
}

TEST(Frames, EachFrameOfAFourDimensionalNiftiPlainAndGzipped) {
    TempDir dir;
    vots::test::NiftiSpec spec;
    spec.datatype = 16;
    spec.bitpix = 32;
    spec.dim[0] = 4;
    spec.dim[4] = 3;
    std::string payload;
    const std::vector<double> base = vots::test::fixtureValues(ScalarType::Float32);
    for (int frame = 0; frame < 3; ++frame) {
        std::vector<double> values = base;
        for (double& v : values)
            v += 1000.0 * frame;
        payload += vots::test::encode(values, ScalarType::Float32, false);
    }
    const std::string plain = dir.write("four.nii", vots::test::niftiHeader(spec) + payload);
    const std::string gzipped = (dir.path() / "four.nii.gz").string();
    vots::test::appendGzip(gzipped, vots::test::niftiHeader(spec) + payload);
    for (const std::string& path : {plain, gzipped}) {
        EXPECT_EQ(volumeHeaderInfo(path).frames, 3u);
        EXPECT_EQ(volumeHeaderInfo(path).dims[2], 3u);
        for (int frame = 0; frame < 3; ++frame) {
            const Volume v = loadVolume(path, std::nullopt, SampleStorage::Float, {}, frame);
            ASSERT_EQ(v.values.size(), base.size());
            for (std::size_t i = 0; i < base.size(); ++i)
                ASSERT_EQ(v.values[i], static_cast<float>(base[i] + 1000.0 * frame)) << path << " " << frame;
        }
        EXPECT_THROW(loadVolume(path, std::nullopt, SampleStorage::Float, {}, 3), InputError);
    }
    // A 3D format has frame 0 only.
    EXPECT_THROW(loadVolume(VOTS_TEST_DATA_DIR "/blobs_64x64x64_uint8.nrrd", std::nullopt,
                            SampleStorage::Float, {}, 1),
                 InputError);
}
