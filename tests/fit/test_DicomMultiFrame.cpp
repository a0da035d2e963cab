// Multi-frame DICOM instances (one file of several frames, Enhanced CT style) written by GDCM at test time:
// a stack of slices as one 3D volume, time points as frames, the rescale in the functional groups, and a
// NumberOfFrames larger than the pixel data.
#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"

#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomMultiFrameWriter.h"

#include <gtest/gtest.h>

#include <string>

namespace vots::test {
namespace {

/// Time point t: HU-like values that differ at every sample and between time points.
fit::Volume timePoint(int t) {
    return sampleVolume({12, 10, 8},
                        [t](int x, int y, int z) { return -900.0 + 37.0 * t + x + 13 * y + 131 * z; },
                        {0.8, 0.7, 1.5});
}

void expectSamples(const fit::Volume& loaded, const fit::Volume& expected, const std::string& what) {
    ASSERT_EQ(loaded.dims, expected.dims) << what;
    ASSERT_EQ(loaded.values.size(), expected.values.size()) << what;
    for (std::size_t i = 0; i < expected.values.size(); ++i)
        ASSERT_EQ(loaded.values[i], expected.values[i]) << what << " sample " << i;
}

/// Writes `timePoints` time points as instance.dcm in a folder of its own and returns the folder.
std::string writeInstance(const TempDir& dir, int timePoints, const MultiFrameOptions& options) {
    std::vector<fit::Volume> volumes;
    for (int t = 0; t < timePoints; ++t)
        volumes.push_back(timePoint(t));
    const std::string folder = dir.file("instance");
    std::filesystem::create_directories(folder);
    writeMultiFrameDicom(volumes, folder + "/instance.dcm", options);
    return folder;
}

fit::Volume loadFrame(const std::string& folder, int frame) {
    return fit::loadVolume(folder, std::nullopt, fit::SampleStorage::Float, {}, frame);
}

TEST(DicomMultiFrame, AStackOfSlicesInOneInstanceIsOneVolumePlacedByItsFunctionalGroups) {
    TempDir dir;
    MultiFrameOptions options;
    options.slicesDescending = true; // frame 1 is the top slice: the positions order them
    const std::string folder = writeInstance(dir, 1, options);
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(folder);
    EXPECT_EQ(header.frames, 1u);
    EXPECT_EQ(header.dims, (std::array<std::uint64_t, 3>{12, 10, 8}));
    const fit::Volume loaded = loadFrame(folder, 0);
    EXPECT_NEAR(loaded.spacing[0], 0.8, 1e-9);
    EXPECT_NEAR(loaded.spacing[1], 0.7, 1e-9);
    EXPECT_NEAR(loaded.spacing[2], 1.5, 1e-9);
    EXPECT_NEAR(loaded.origin[0], -20, 1e-9);
    EXPECT_NEAR(loaded.origin[1], 10, 1e-9);
    EXPECT_NEAR(loaded.origin[2], 35, 1e-9);
    expectSamples(loaded, timePoint(0), "stack");
}

TEST(DicomMultiFrame, TemporalPositionsInOneInstanceAreFrames) {
    TempDir dir;
    const std::string folder = writeInstance(dir, 3, MultiFrameOptions{});
    EXPECT_EQ(fit::volumeHeaderInfo(folder).frames, 3u);
    for (int t = 0; t < 3; ++t) {
        const fit::Volume loaded = loadFrame(folder, t);
        expectSamples(loaded, timePoint(t), "frame " + std::to_string(t));
        const fit::PlanesOfGrid planes =
            fit::loadVolumePlanes(folder, 2, 5, std::nullopt, fit::SampleStorage::Float, {}, t);
        EXPECT_EQ(planes.planes.values, fit::planesOf(loaded, 2, 5).values) << "frame " << t;
    }
    try {
        loadFrame(folder, 3);
        FAIL() << "frame 3 of 3 loaded";
    } catch (const fit::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("it holds 3 frames"), std::string::npos) << e.what();
    }
}

TEST(DicomMultiFrame, CompressedFramesDecodeToTheSameSamples) {
    TempDir dir;
    MultiFrameOptions options;
    options.syntax = "rle";
    const std::string folder = writeInstance(dir, 2, options);
    EXPECT_EQ(fit::volumeHeaderInfo(folder).frames, 2u);
    expectSamples(loadFrame(folder, 1), timePoint(1), "RLE frame 1");
}

TEST(DicomMultiFrame, WithoutFunctionalGroupsTheFramesStackAtTheSpacingBetweenSlices) {
    TempDir dir;
    MultiFrameOptions options;
    options.functionalGroups = false;
    const std::string folder = writeInstance(dir, 1, options);
    const fit::Volume loaded = loadFrame(folder, 0);
    EXPECT_NEAR(loaded.spacing[2], 1.5, 1e-9);
    EXPECT_NEAR(loaded.origin[2], 35, 1e-9);
    expectSamples(loaded, timePoint(0), "stack without groups");
}

TEST(DicomMultiFrame, ANumberOfFramesLargerThanThePixelDataIsRefused) {
    TempDir dir;
    MultiFrameOptions options;
    options.announcedFrames = 80; // 8 frames written
    const std::string folder = writeInstance(dir, 1, options);
    try {
        fit::volumeHeaderInfo(folder);
        FAIL() << "80 frames announced over the pixels of 8 were accepted";
    } catch (const fit::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("announces 80 frames (NumberOfFrames)"), std::string::npos)
            << e.what();
    }
    // Compressed, where the file's size does not tell: the decode finds the frames missing.
    TempDir rleDir;
    options.syntax = "rle";
    const std::string rle = writeInstance(rleDir, 1, options);
    EXPECT_THROW(loadFrame(rle, 0), fit::InputError);
}

} // namespace
} // namespace vots::test
