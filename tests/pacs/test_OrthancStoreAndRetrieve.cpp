// STOW-RS into the real Orthanc of the pacs fixture, and WADO-RS retrieves back: bytes, progress, spool.
#include "FolderFiles.h"
#include "OrthancState.h"
#include "SampleVolume.h"
#include "TempDir.h"
#include "dicom/DicomSeriesWriter.h"

#include "vots/fit/DicomSeries.h"
#include "vots/fit/Error.h"
#include "vots/pacs/QidoSearch.h"
#include "vots/pacs/SeriesRetrieve.h"
#include "vots/pacs/StowStore.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

namespace {

using namespace vots::pacs;
using namespace vots::test;
namespace fs = std::filesystem;

TEST(OrthancStoreAndRetrieve, StoredSeriesComesBackSampleForSample) {
    TempDir dir;
    const vots::fit::Volume volume = sampleVolume(
        {20, 16, 12}, [](int x, int y, int z) { return x * 3 + y * 5 - z * 7; }, {0.7, 0.7, 1.5});
    DicomWriteOptions options;
    options.seriesUid = "1.2.826.0.1.3680043.10.1234.301";
    options.description = "stored by STOW";
    writeDicomSeries(volume, dir.file("series"), options);
    const StoreReport report =
        storeInstances(orthancEndpoint(), orthancAccess(), filesOf(dir.file("series")));
    EXPECT_EQ(report.stored, 12);

    const auto series = searchSeries(orthancEndpoint(), orthancAccess(), options.seriesUid + ".0");
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].instanceCount, 12);
    EXPECT_EQ(series[0].description, "stored by STOW");

    fs::create_directory(dir.file("spool"));
    std::vector<std::pair<int, int>> progress;
    SeriesRetrieveOptions retrieve;
    retrieve.spoolParent = dir.file("spool");
    retrieve.progress = [&](int received, int total) { progress.emplace_back(received, total); };
    std::array<std::uint64_t, 3> admitted{};
    retrieve.admit = [&](const vots::fit::VolumeHeaderInfo& header) {
        admitted = header.dims;
        // Longer than Orthanc keeps an idle connection (1 s): the series request must not depend on it.
        std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    };
    {
        const RetrievedSeries retrieved =
            retrieveSeries(orthancSeries(options.seriesUid), orthancAccess(), retrieve);
        EXPECT_FALSE(retrieved.perInstance) << retrieved.seriesProblem;
        EXPECT_EQ(retrieved.instanceCount, 12);
        const vots::fit::Volume back = vots::fit::loadDicomSeries(retrieved.folder());
        const vots::fit::Volume direct = vots::fit::loadDicomSeries(dir.file("series"));
        EXPECT_EQ(back.dims, direct.dims);
        EXPECT_EQ(back.values, direct.values);
        EXPECT_EQ(back.values, volume.values);
    }
    EXPECT_TRUE(fs::is_empty(dir.file("spool"))) << "the spool folder outlived the retrieved series";
    EXPECT_EQ(admitted, (std::array<std::uint64_t, 3>{20, 16, 12}));
    ASSERT_EQ(progress.size(), 12u);
    for (int i = 0; i < 12; ++i)
        EXPECT_EQ(progress[static_cast<std::size_t>(i)], std::make_pair(i + 1, 12));
}

TEST(OrthancStoreAndRetrieve, ARefusedInstanceIsOneClearLine) {
    TempDir dir;
    const std::string junk = dir.write("junk.dcm", std::string(300, 'x'));
    try {
        storeInstances(orthancEndpoint(), orthancAccess(), {junk});
        FAIL() << "a file that is not DICOM was stored";
    } catch (const vots::fit::InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.find(orthancAccess().auth.secret), std::string::npos) << message;
        EXPECT_NE(message.find("dicomweb+http://127.0.0.1:"), std::string::npos) << message;
    }
}

TEST(OrthancStoreAndRetrieve, RefusalBeforeThePixelsLeavesNoSpool) {
    TempDir dir;
    SeriesRetrieveOptions retrieve;
    retrieve.spoolParent = dir.path().string();
    retrieve.admit = [](const vots::fit::VolumeHeaderInfo& header) {
        EXPECT_EQ(header.dims, (std::array<std::uint64_t, 3>{256, 256, 108}));
        throw vots::fit::InputError("too big for this test");
    };
    EXPECT_THROW(retrieveSeries(orthancSeries(CRANIUM_SERIES), orthancAccess(), retrieve),
                 vots::fit::InputError);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(OrthancStoreAndRetrieve, ACancelledRetrieveThrowsAndLeavesNoSpool) {
    TempDir dir;
    std::atomic<bool> cancel{false};
    SeriesRetrieveOptions retrieve;
    retrieve.spoolParent = dir.path().string();
    retrieve.cancel = &cancel;
    retrieve.progress = [&](int received, int) {
        if (received == 10) cancel = true;
    };
    EXPECT_THROW(retrieveSeries(orthancSeries(CRANIUM_SERIES), orthancAccess(), retrieve),
                 vots::fit::InputError);
    EXPECT_TRUE(fs::is_empty(dir.path()));
}

} // namespace
