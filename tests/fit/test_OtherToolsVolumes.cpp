// Volumes other tools wrote (Debian's python3-nibabel test data): NIfTI-1, NIfTI-2, MGZ, NaN, 4D frames,
// each checked against nibabel's own reading of the file (tests/fit/nibabel_reference.py, run here).
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/Verify.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

using namespace vots::fit;
using nlohmann::json;

namespace {

const std::string NIBABEL_DATA = "/usr/lib/python3/dist-packages/nibabel/tests/data/";

// nibabel's reading of one frame, from Debian's interpreter (where python3-nibabel is installed).
json nibabelReading(const std::string& path, int frame) {
    const std::string command = "/usr/bin/python3 " VOTS_SOURCE_DIR "/tests/fit/nibabel_reference.py '" +
                                path + "' " + std::to_string(frame);
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    if (!pipe) throw std::runtime_error("cannot run " + command);
    std::string out;
    char buffer[4096];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe.get()))
        out.append(buffer, n);
    return json::parse(out);
}

bool isNoData(double v) {
    return !std::isfinite(v);
}

// Every check of one frame: grid, spacing, orientation, the NaN count, the finite sum and spread samples.
void expectAsNibabelReads(const std::string& name, int frame) {
    SCOPED_TRACE(name + " frame " + std::to_string(frame));
    const std::string path = NIBABEL_DATA + name;
    const json ref = nibabelReading(path, frame);
    const Volume v = loadVolume(path, std::nullopt, SampleStorage::Float, {}, frame);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(v.dims[a], ref["dims"][a].get<int>());
        // The grid step is the length of the affine's column (for test.mgz, whose direction cosines
        // are not unit vectors, not the voxel size nibabel calls its zoom).
        const json& affine = ref["affine"];
        const double step =
            std::hypot(affine[0][a].get<double>(), affine[1][a].get<double>(), affine[2][a].get<double>());
        EXPECT_NEAR(v.spacing[a], step, 1e-5 * step);
    }
    EXPECT_EQ(volumeHeaderInfo(path).frames, ref["frames"].get<std::uint64_t>());
    ASSERT_TRUE(v.orientationKnown);
    for (int row = 0; row < 3; ++row) {
        const json& r = ref["affine"][row];
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(v.patientAxes[a][row] * v.spacing[a], r[a].get<double>(), 1e-4) << "row " << row;
        EXPECT_NEAR(v.origin[row], r[3].get<double>(), 1e-3) << "row " << row;
    }
    EXPECT_EQ(v.nonFiniteCount(), ref["non_finite"].get<std::size_t>());
    double sum = 0.0;
    for (std::size_t i = 0; i < v.values.size(); ++i)
        sum += isNoData(v.values[i]) ? 0.0 : double{v.values[i]};
    const double refSum = ref["finite_sum"].get<double>();
    EXPECT_NEAR(sum, refSum, 1e-6 * std::max(1.0, std::fabs(refSum)));
    for (const json& s : ref["samples"]) {
        const float value = v.at(s[0].get<int>(), s[1].get<int>(), s[2].get<int>());
        if (s[3].is_null())
            EXPECT_TRUE(isNoData(value)) << s.dump();
        else
            EXPECT_NEAR(value, s[3].get<double>(), 1e-6 * std::max(1.0, std::fabs(s[3].get<double>())))
                << s.dump();
    }
}

} // namespace

TEST(OtherToolsVolumes, ThreeDimensionalFilesReadAsNibabelReadsThem) {
    for (const char* name :
         {"anatomical.nii", "standard.nii.gz", "reoriented_anat_moved.nii", "resampled_anat_moved.nii"})
        expectAsNibabelReads(name, 0);
}

TEST(OtherToolsVolumes, EveryFrameOfTheFourDimensionalFiles) {
    for (const auto& [name, frames] : {std::pair<const char*, int>{"example4d.nii.gz", 2},
                                       {"functional.nii", 20},
                                       {"example_nifti2.nii.gz", 2},
                                       {"test.mgz", 2}}) {
        EXPECT_EQ(volumeHeaderInfo(NIBABEL_DATA + name).frames, static_cast<std::uint64_t>(frames)) << name;
        for (int frame = 0; frame < frames; ++frame)
            expectAsNibabelReads(name, frame);
    }
}

TEST(OtherToolsVolumes, FramesOutOfRangeNameTheCount) {
    const auto errorOf = [](const std::string& name, int frame) {
        try {
            loadVolume(NIBABEL_DATA + name, std::nullopt, SampleStorage::Float, {}, frame);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(errorOf("functional.nii", 20).find("has no frame 20: it holds 20 frames (0 to 19)"),
              std::string::npos);
    EXPECT_NE(errorOf("test.mgz", 2).find("has no frame 2: it holds 2 frames"), std::string::npos);
    EXPECT_NE(errorOf("example_nifti2.nii.gz", -1).find("has no frame -1"), std::string::npos);
    EXPECT_NE(errorOf("anatomical.nii", 1).find("has no frame 1: it holds 1 frame (0)"), std::string::npos);
}

TEST(OtherToolsVolumes, NanSamplesOfAResampledVolumeAreLeftOut) {
    const Volume v = loadVolume(NIBABEL_DATA + "resampled_anat_moved.nii");
    ASSERT_EQ(v.nonFiniteCount(), 153u);
    FitOptions options;
    const auto range = v.valueRange();
    options.eps = 0.02f * (range[1] - range[0]);
    options.background = defaultBackground(range);
    const FitResult fit = fitVotSpace(v, options);
    // verifyVotSpace: no Vot holds a NaN, every finite sample of a Vot is within eps, every cell with
    // finite corners above the threshold is covered.
    const VerifyReport report = verifyVotSpace(fit.space, v, std::nullopt);
    EXPECT_TRUE(report.ok) << report.firstProblem;
    EXPECT_EQ(report.violations, 0u);
    EXPECT_GT(report.samplesChecked, 0u);
    // Omitted cells, no-data ones counting as the lowest finite sample, stand for a value below the
    // threshold, as cells below it do.
    ASSERT_TRUE(fit.space.backgroundFill.has_value());
    EXPECT_GE(*fit.space.backgroundFill, range[0]);
    EXPECT_LT(*fit.space.backgroundFill, *options.background);
}
