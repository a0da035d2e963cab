// RetrievedSeriesCache: kept series are found by their instance list, and the least recently opened go first.
#include "TempDir.h"
#include "dicomweb/RetrievedSeriesCache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using vots::server::RetrievedSeriesCache;
using vots::server::retrievedSeriesKey;

/// A retrieve's spool folder in the cache's spool parent with `files` instance files of `bytes` bytes each.
vots::pacs::RetrievedSeries spooled(const RetrievedSeriesCache& cache, int files, std::size_t bytes) {
    vots::pacs::RetrievedSeries retrieved{vots::pacs::SpoolFolder(cache.spoolParent().string())};
    for (int i = 0; i < files; ++i) {
        std::ofstream out(fs::path(retrieved.folder()) / ("instance-" + std::to_string(i)), std::ios::binary);
        out << std::string(bytes, static_cast<char>('a' + i));
    }
    retrieved.instanceCount = files;
    return retrieved;
}

vots::server::KeptSeries origin(const std::string& seriesUid) {
    return {"pacs", seriesUid + ".0", seriesUid, {}};
}

const std::vector<std::string> SOPS_A = {"1.2.3.1", "1.2.3.2"};
const std::vector<std::string> SOPS_B = {"1.2.4.1", "1.2.4.2"};
const std::vector<std::string> SOPS_C = {"1.2.5.1", "1.2.5.2"};

TEST(RetrievedSeriesCache, FindsAKeptSeriesOnlyWhileItsInstanceListIsTheSame) {
    vots::test::TempDir dir;
    RetrievedSeriesCache cache(dir.path() / "dicomweb", 1 << 20);
    EXPECT_FALSE(cache.find("1.2.3", SOPS_A));
    const fs::path kept = cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 2, 100));
    EXPECT_EQ(kept.filename(), retrievedSeriesKey("1.2.3", SOPS_A));
    EXPECT_EQ(std::distance(fs::directory_iterator(kept), fs::directory_iterator()), 2);
    const auto found = cache.find("1.2.3", {"1.2.3.2", "1.2.3.1"}); // the order the PACS lists them in
    ASSERT_TRUE(found);
    EXPECT_EQ(*found, kept);
    EXPECT_FALSE(cache.find("1.2.3", {"1.2.3.1", "1.2.3.2", "1.2.3.3"}))
        << "an instance more is another series";
    EXPECT_FALSE(cache.find("1.2.3", {"1.2.3.1"})) << "an instance less is another series";
    EXPECT_TRUE(fs::is_empty(cache.spoolParent())) << "the spool folder was moved, not copied";
    const auto listed = cache.kept();
    ASSERT_EQ(listed.size(), 1u);
    EXPECT_EQ(listed[0].service, "pacs");
    EXPECT_EQ(listed[0].studyUid, "1.2.3.0");
    EXPECT_EQ(listed[0].seriesUid, "1.2.3");
    EXPECT_EQ(listed[0].folder, kept);
}

TEST(RetrievedSeriesCache, RemovesTheSpoolsOfProcessesThatNoLongerRun) {
    vots::test::TempDir dir;
    const fs::path root = dir.path() / "dicomweb";
    fs::create_directories(root / "spool-999999999" / "vots-dicomweb-abcdef"); // no such pid (above pid_max)
    fs::create_directories(root / "spool-1" / "vots-dicomweb-abcdef");         // init runs
    RetrievedSeriesCache cache(root, 1 << 20);
    EXPECT_FALSE(fs::exists(root / "spool-999999999"));
    EXPECT_TRUE(fs::exists(root / "spool-1"));
    EXPECT_TRUE(fs::is_directory(cache.spoolParent()));
}

TEST(RetrievedSeriesCache, AFolderWithoutItsRecordIsNotUsed) {
    vots::test::TempDir dir;
    RetrievedSeriesCache cache(dir.path() / "dicomweb", 1 << 20);
    const fs::path kept = cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 2, 100));
    fs::remove(kept.string() + ".json"); // as a server that stopped between the move and the record leaves it
    EXPECT_FALSE(cache.find("1.2.3", SOPS_A));
    EXPECT_TRUE(cache.kept().empty());
}

TEST(RetrievedSeriesCache, RemovesTheLeastRecentlyOpenedBeyondItsBudget) {
    vots::test::TempDir dir;
    RetrievedSeriesCache cache(dir.path() / "dicomweb", 2500); // room for two series of 1000 bytes
    cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 2, 500));
    cache.keep(origin("1.2.4"), SOPS_B, spooled(cache, 2, 500));
    ASSERT_TRUE(cache.find("1.2.3", SOPS_A)); // opened again: now the more recent of the two
    cache.keep(origin("1.2.5"), SOPS_C, spooled(cache, 2, 500));
    EXPECT_TRUE(cache.find("1.2.3", SOPS_A));
    EXPECT_FALSE(cache.find("1.2.4", SOPS_B));
    EXPECT_FALSE(fs::exists(cache.root() / retrievedSeriesKey("1.2.4", SOPS_B)));
    EXPECT_TRUE(cache.find("1.2.5", SOPS_C));
}

TEST(RetrievedSeriesCache, KeepsTheNewestSeriesEvenOverTheBudget) {
    vots::test::TempDir dir;
    RetrievedSeriesCache cache(dir.path() / "dicomweb", 10);
    cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 2, 500));
    cache.keep(origin("1.2.4"), SOPS_B, spooled(cache, 2, 500));
    EXPECT_FALSE(cache.find("1.2.3", SOPS_A));
    EXPECT_TRUE(cache.find("1.2.4", SOPS_B));
}

TEST(RetrievedSeriesCache, AFolderThatCannotBeMadeFallsBackToATemporaryOne) {
    vots::test::TempDir dir;
    dir.write("not-a-folder", "x");
    fs::path root;
    {
        RetrievedSeriesCache cache(dir.path() / "not-a-folder" / "dicomweb", 1 << 20);
        root = cache.root();
        EXPECT_NE(root.parent_path(), dir.path() / "not-a-folder");
        cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 1, 10));
        EXPECT_TRUE(cache.find("1.2.3", SOPS_A));
    }
    EXPECT_FALSE(fs::exists(root));
}

TEST(RetrievedSeriesCache, WithoutAFolderUsesATemporaryOneItRemoves) {
    fs::path root;
    {
        RetrievedSeriesCache cache({}, 1 << 20);
        root = cache.root();
        cache.keep(origin("1.2.3"), SOPS_A, spooled(cache, 1, 10));
        EXPECT_TRUE(cache.find("1.2.3", SOPS_A));
    }
    EXPECT_FALSE(fs::exists(root));
}

} // namespace
