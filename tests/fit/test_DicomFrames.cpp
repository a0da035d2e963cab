// DICOM series with several time points at each position (perfusion, cardiac phases), written by the
// project's GDCM writer: the frame count, each frame's samples, the time order, and the frame errors.
#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"

#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vots::test {
namespace {

constexpr int TIME_POINTS = 3;

/// Time point t: a ball of contrast that grows brighter, HU-like, so every frame's samples differ.
fit::Volume phase(int t) {
    return sampleVolume({12, 10, 8},
                        [t](int x, int y, int z) {
                            const double r = std::hypot(x - 5.5, y - 4.5, z - 3.5);
                            return r < 4 ? 100.0 + 200.0 * t + x : -1000.0;
                        },
                        {0.8, 0.8, 1.5});
}

/// One series of TIME_POINTS frames; the files of each time point written in `order` (time point k as
/// TemporalPositionIdentifier order[k] + 1), so the reader must order them by the tag, not by file names.
std::string writeFourDimensionalSeries(const TempDir& dir, const std::array<int, TIME_POINTS>& order) {
    const std::string folder = dir.file("perfusion");
    for (int k = 0; k < TIME_POINTS; ++k) {
        DicomWriteOptions o;
        o.filePrefix = "p" + std::to_string(k);
        o.order = DicomFileOrder::Shuffled;
        o.temporalPosition = order[k] + 1;
        writeDicomSeries(phase(order[k]), folder, o);
    }
    return folder;
}

TEST(DicomFrames, EachTimePointIsAFrameInTheOrderOfItsTemporalPosition) {
    TempDir dir;
    const std::string folder = writeFourDimensionalSeries(dir, {2, 0, 1});
    const fit::VolumeHeaderInfo header = fit::volumeHeaderInfo(folder);
    EXPECT_EQ(header.frames, static_cast<std::uint64_t>(TIME_POINTS));
    EXPECT_EQ(header.dims, (std::array<std::uint64_t, 3>{12, 10, 8}));
    for (int t = 0; t < TIME_POINTS; ++t) {
        const fit::Volume loaded = fit::loadVolume(folder, std::nullopt, fit::SampleStorage::Float, {}, t);
        const fit::Volume expected = phase(t);
        ASSERT_EQ(loaded.dims, expected.dims);
        EXPECT_NEAR(loaded.spacing[2], 1.5, 1e-9);
        ASSERT_EQ(loaded.values.size(), expected.values.size());
        for (std::size_t i = 0; i < expected.values.size(); ++i)
            ASSERT_EQ(loaded.values[i], expected.values[i]) << "frame " << t << " sample " << i;
        // A rank's planes of the frame are the frame's planes.
        const fit::PlanesOfGrid planes =
            fit::loadVolumePlanes(folder, 3, 6, std::nullopt, fit::SampleStorage::Float, {}, t);
        const fit::Volume cut = fit::planesOf(loaded, 3, 6);
        EXPECT_EQ(planes.planes.values, cut.values) << "frame " << t;
        EXPECT_EQ(planes.whole.dims, loaded.dims);
    }
}

TEST(DicomFrames, AFrameTheSeriesDoesNotHoldNamesTheCount) {
    TempDir dir;
    const std::string folder = writeFourDimensionalSeries(dir, {0, 1, 2});
    try {
        fit::loadVolume(folder, std::nullopt, fit::SampleStorage::Float, {}, 3);
        FAIL() << "frame 3 of 3 loaded";
    } catch (const fit::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("has no frame 3: it holds 3 frames (0 to 2)"), std::string::npos)
            << e.what();
    }
    // A 3D series has frame 0 only.
    DicomWriteOptions flat;
    writeDicomSeries(phase(0), dir.file("flat"), flat);
    EXPECT_EQ(fit::volumeHeaderInfo(dir.file("flat")).frames, 1u);
    EXPECT_THROW(fit::loadVolume(dir.file("flat"), std::nullopt, fit::SampleStorage::Float, {}, 1),
                 fit::InputError);
}

TEST(DicomFrames, PositionsHoldingDifferentCountsAreRefused) {
    TempDir dir;
    const std::string folder = writeFourDimensionalSeries(dir, {0, 1, 2});
    DicomWriteOptions extra; // a fourth time point with one slice missing
    extra.filePrefix = "p3";
    extra.temporalPosition = 4;
    extra.dropSlice = 2;
    writeDicomSeries(phase(3), folder, extra);
    try {
        fit::volumeHeaderInfo(folder);
        FAIL() << "a series with 4 images at some positions and 3 at one was read";
    } catch (const fit::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("not one per time point everywhere"), std::string::npos)
            << e.what();
    }
}

TEST(DicomFrames, TwoImagesAtOnePositionAndOneTimeAreRefused) {
    TempDir dir;
    DicomWriteOptions a, b;
    a.filePrefix = "a";
    a.temporalPosition = 1;
    b.filePrefix = "b";
    b.temporalPosition = 1; // the same time point twice
    writeDicomSeries(phase(0), dir.file("twice"), a);
    writeDicomSeries(phase(1), dir.file("twice"), b);
    EXPECT_THROW(fit::volumeHeaderInfo(dir.file("twice")), fit::InputError);
}

} // namespace
} // namespace vots::test
