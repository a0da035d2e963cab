// DICOM series folders as server datasets over loopback: named after the folder (and series), rendered.
#include "SampleVolume.h"
#include "ServerFixture.h"
#include "datasets/DatasetRegistry.h"
#include "dicom/DicomSeriesWriter.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>

namespace vots::test {
namespace {

fit::Volume ball() {
    return sampleVolume(
        {20, 18, 12},
        [](int x, int y, int z) { return std::hypot(x - 9.5, y - 8.5, z - 5.5) < 5 ? 800.0 : -1000.0; },
        {1.0, 1.0, 1.5});
}

std::vector<std::string> namesIn(const nlohmann::json& list) {
    std::vector<std::string> names;
    for (const auto& d : list["datasets"])
        names.push_back(d["name"].get<std::string>());
    return names;
}

TEST(ServerDicom, SeriesFoldersAreDatasetsThatRender) {
    ServerWorld world;
    DicomWriteOptions single;
    single.syntax = "rle";
    single.order = DicomFileOrder::Descending;
    writeDicomSeries(ball(), (world.data() / "ct").string(), single);
    DicomWriteOptions axial;
    axial.seriesUid = "1.2.3.7.1";
    axial.description = "axial";
    axial.filePrefix = "a";
    DicomWriteOptions thin = axial;
    thin.seriesUid = "1.2.3.7.2";
    thin.description = "thin";
    thin.filePrefix = "b";
    writeDicomSeries(ball(), (world.data() / "study").string(), axial);
    writeDicomSeries(ball(), (world.data() / "study").string(), thin);
    std::filesystem::create_directories(world.data() / "notes");
    world.dir().write("data/notes/readme.txt", "no images here");

    LoopbackServer server(world.options());
    auto c = server.client();
    const auto names = namesIn(bodyJson(c->Get("/api/datasets")));
    for (const char* expected : {"ct", "study-axial", "study-thin"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    EXPECT_EQ(std::find(names.begin(), names.end(), "notes"), names.end());

    for (const char* dataset : {"ct", "study-thin"}) {
        const auto res = c->Get((std::string("/render?dataset=") + dataset + "&size=48x48&eps=20").c_str());
        ASSERT_TRUE(res) << dataset;
        ASSERT_EQ(res->status, 200) << dataset << ": " << res->body;
        EXPECT_EQ(res->body.substr(1, 3), "PNG");
        EXPECT_GT(std::stoi(res->get_header_value("X-Vots-Vot-Count")), 0) << dataset;
    }
}

// A damaged file found by fuzz_dicom (an element length of gigabytes, which took the start-up scan's child
// to 3.6 GB) costs its folder only: the server starts and serves the other series.
TEST(ServerDicom, AFolderWithADamagedFileIsSkippedWithinASmallPeak) {
    ServerWorld world;
    writeDicomSeries(ball(), (world.data() / "ct").string(), {});
    std::filesystem::create_directories(world.data() / "damaged");
    std::filesystem::copy_file(std::filesystem::path(VOTS_SOURCE_DIR) /
                                   "tests/fuzz/regressions/fuzz_dicom/huge-length-in-header",
                               world.data() / "damaged" / "slice-0001.dcm");

    LoopbackServer server(world.options());
    auto c = server.client();
    const auto names = namesIn(bodyJson(c->Get("/api/datasets")));
    EXPECT_NE(std::find(names.begin(), names.end(), "ct"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "damaged"), names.end());
    const auto res = c->Get("/render?dataset=ct&size=48x48&eps=20");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << res->body;
    rusage children{};
    getrusage(RUSAGE_CHILDREN, &children);
    EXPECT_LT(children.ru_maxrss, 500 * 1024) << "peak of the DICOM readers' children, in KB";
}

TEST(ServerDicom, NamesFallBackToTheUidWhenDescriptionsDoNotTellSeriesApart) {
    const std::vector<fit::DicomSeriesSummary> same = {{"1.2.840.5.11", "CT", 10},
                                                       {"1.2.840.5.12", "CT", 20}};
    const auto names = server::dicomDatasetNames("scan 1", same);
    ASSERT_EQ(names.size(), 2u);
    EXPECT_EQ(names.at("scan_1-840_5_11"), "1.2.840.5.11");
    EXPECT_EQ(names.at("scan_1-840_5_12"), "1.2.840.5.12");
    EXPECT_EQ(server::dicomDatasetNames("ct", {{"9.9", "", 3}}).at("ct"), "9.9");
    EXPECT_TRUE(server::dicomDatasetNames("empty", {}).empty());
}

} // namespace
} // namespace vots::test
