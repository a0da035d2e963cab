// fit::DicomSeriesIntake, which reads a series from the PACS as its files arrive: the same volume as the
// folder reader in any arrival order, another grid handed back to the folder reader, damaged files refused.
#include "FolderFiles.h"
#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include "vots/fit/DicomIntake.h"
#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

namespace {

using namespace vots;
using namespace vots::test;
namespace fs = std::filesystem;

fit::VolumeHeaderInfo gridOf(const fit::Volume& volume) {
    fit::VolumeHeaderInfo header;
    for (int a = 0; a < 3; ++a)
        header.dims[a] = static_cast<std::uint64_t>(volume.dims[a]);
    header.sourceType = volume.sourceType;
    return header;
}

class DicomIntake : public ::testing::Test {
protected:
    DicomIntake() {
        const fit::Volume volume = sampleVolume(
            {24, 18, 14}, [](int x, int y, int z) { return x * 3 + y * 5 - z * 7 - 1000; }, {0.7, 0.6, 1.5});
        DicomWriteOptions options;
        options.order = DicomFileOrder::Shuffled; // file names say nothing of the slice order
        writeDicomSeries(volume, mDir.file("series"), options);
        mFolderRead = fit::loadDicomSeries(mDir.file("series"), {}, fit::SampleStorage::Source);
    }

    TempDir mDir;
    fit::Volume mFolderRead;
};

TEST_F(DicomIntake, FilesInAnyOrderGiveTheFolderReadersVolume) {
    std::vector<std::string> files = filesOf(mDir.file("series"));
    std::mt19937 shuffle(7);
    std::shuffle(files.begin(), files.end(), shuffle);
    fit::DicomSeriesIntake intake(gridOf(mFolderRead), fit::SampleStorage::Source);
    // From two threads, as the per-instance retrieve adds them, with pauses longer than the child's idle
    // word.
    std::thread other([&] {
        for (std::size_t i = 1; i < files.size(); i += 2)
            intake.add(files[i]);
    });
    for (std::size_t i = 0; i < files.size(); i += 2) {
        intake.add(files[i]);
        if (i == 4) std::this_thread::sleep_for(std::chrono::milliseconds(1300));
    }
    other.join();
    const fit::DicomIntakeResult read = intake.finish("series");
    EXPECT_EQ(read.images, 14);
    EXPECT_EQ(read.files, 14);
    ASSERT_TRUE(read.volume.has_value());
    EXPECT_EQ(read.volume->dims, mFolderRead.dims);
    EXPECT_EQ(read.volume->spacing, mFolderRead.spacing);
    EXPECT_EQ(read.volume->origin, mFolderRead.origin);
    EXPECT_EQ(read.volume->patientAxes, mFolderRead.patientAxes);
    EXPECT_EQ(read.volume->sourceType, mFolderRead.sourceType);
    ASSERT_TRUE(mFolderRead.isCompact());
    EXPECT_TRUE(read.volume->compact == mFolderRead.compact) << "the samples differ from the folder's";
    EXPECT_EQ(read.volume->contentCrc(), mFolderRead.contentCrc());
    // Combined from the slices in arrival order, then put in z order: the volume's own.
    EXPECT_EQ(read.contentCrc, mFolderRead.contentCrc());
    EXPECT_EQ(read.valueRange, mFolderRead.valueRange());
    EXPECT_NE(read.valueRange[0], read.valueRange[1]);
}

TEST_F(DicomIntake, FloatStorageMatchesTheFolderReaderToo) {
    const fit::Volume floats = fit::loadDicomSeries(mDir.file("series"));
    fit::DicomSeriesIntake intake(gridOf(mFolderRead), fit::SampleStorage::Float);
    for (const std::string& file : filesOf(mDir.file("series")))
        intake.add(file);
    const fit::DicomIntakeResult read = intake.finish("series");
    ASSERT_TRUE(read.volume.has_value());
    EXPECT_EQ(read.volume->values, floats.values);
    EXPECT_EQ(read.contentCrc, floats.contentCrc());
    EXPECT_EQ(read.valueRange, floats.valueRange());
}

TEST_F(DicomIntake, AnotherGridThanAnnouncedIsLeftToTheFolderReader) {
    fit::VolumeHeaderInfo fewer = gridOf(mFolderRead);
    fewer.dims[2] = 13; // one more file than announced
    fit::VolumeHeaderInfo wider = gridOf(mFolderRead);
    wider.dims[0] = 25;
    fit::VolumeHeaderInfo floats = gridOf(mFolderRead);
    floats.sourceType = fit::ScalarType::Float32;
    for (const fit::VolumeHeaderInfo& announced : {fewer, wider, floats}) {
        fit::DicomSeriesIntake intake(announced, fit::SampleStorage::Source);
        for (const std::string& file : filesOf(mDir.file("series")))
            intake.add(file);
        const fit::DicomIntakeResult read = intake.finish("series");
        EXPECT_FALSE(read.volume.has_value()) << announced.describe();
        EXPECT_EQ(read.images, 14) << announced.describe();
    }
}

TEST_F(DicomIntake, FilesThatAreNotImagesAreCountedApart) {
    std::ofstream(mDir.file("notes.txt")) << "not a DICOM file";
    fit::DicomSeriesIntake intake(gridOf(mFolderRead), fit::SampleStorage::Source);
    intake.add(mDir.file("notes.txt"));
    for (const std::string& file : filesOf(mDir.file("series")))
        intake.add(file);
    const fit::DicomIntakeResult read = intake.finish("series");
    EXPECT_EQ(read.files, 15);
    EXPECT_EQ(read.images, 14);
    EXPECT_TRUE(read.volume.has_value()); // the caller decides what a stray file means
}

TEST_F(DicomIntake, ADamagedFileFailsNamingIt) {
    std::vector<std::string> files = filesOf(mDir.file("series"));
    fs::resize_file(files[5], fs::file_size(files[5]) / 2); // cut in its pixel data
    fit::DicomSeriesIntake intake(gridOf(mFolderRead), fit::SampleStorage::Source);
    for (const std::string& file : files)
        intake.add(file);
    try {
        (void)intake.finish("series");
        FAIL() << "a truncated file was read";
    } catch (const fit::InputError& e) {
        EXPECT_NE(std::string(e.what()).find(fs::path(files[5]).filename().string()), std::string::npos)
            << e.what();
    }
}

TEST_F(DicomIntake, GivenUpHalfWayItEndsAtOnce) {
    const std::vector<std::string> files = filesOf(mDir.file("series"));
    const auto start = std::chrono::steady_clock::now();
    {
        fit::DicomSeriesIntake intake(gridOf(mFolderRead), fit::SampleStorage::Source);
        for (std::size_t i = 0; i < files.size() / 2; ++i)
            intake.add(files[i]);
    } // a cut retrieve: no finish()
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

} // namespace
