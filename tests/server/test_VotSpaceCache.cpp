// VotSpaceCache and FitKey: exact keys, LRU eviction by bytes, bounded later writes, disk round trip.
#include "fits/CacheMeta.h"
#include "fits/VotSpaceCache.h"
#include "fits/VotSpaceStore.h"

#include "vots/fit/VotSpaceFile.h"

#include "TempDir.h"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

namespace vots::server {
namespace {

/// A 4^3 dataset named after the key, as the registry would load it.
Dataset datasetFor(const FitKey& key) {
    auto volume = std::make_shared<fit::Volume>();
    volume->dims = {4, 4, 4};
    volume->name = key.dataset;
    volume->values.assign(64, 0.f);
    Dataset dataset;
    dataset.name = key.dataset;
    dataset.path = key.dataset + ".nrrd";
    dataset.volume = volume;
    return dataset;
}

std::shared_ptr<const fit::VotSpace> spaceWith(std::size_t vots, const FitKey& key) {
    fit::VotSpace space;
    space.dims = {4, 4, 4};
    space.eps = key.eps;
    fit::Vot vot{};
    vot.box.lo = {0, 0, 0};
    vot.box.hi = {3, 3, 3};
    space.vots.assign(vots, vot);
    fit::FitStats stats;
    stats.seconds = 1.5;
    space.metaJson = cacheMetaFor(key, datasetFor(key), stats, space);
    return std::make_shared<const fit::VotSpace>(std::move(space));
}

TEST(FitKey, TextIsExactAndFileSafe) {
    FitKey a{"blobs", 5.1f, 3, 2.55f, std::nullopt};
    FitKey b = a;
    b.eps = std::nextafter(5.1f, 6.f);
    EXPECT_NE(a.text(), b.text());
    FitKey c = a;
    c.focus = fit::FocusRegion{{1, 2, 3}, 4, 0.5f};
    EXPECT_NE(a.text(), c.text());
    FitKey d = a;
    d.volumeCrc = 0x1234abcdu; // the same name with other contents is another fit
    EXPECT_NE(a.text(), d.text());
    EXPECT_NE(d.text().find("1234abcd"), std::string::npos);
    EXPECT_EQ(c.text().find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-"),
              std::string::npos);
}

TEST(FitKey, TheNormIsPartOfTheKeyAndLeastSquaresKeepsItsOldText) {
    FitKey lsq{"blobs", 5.1f, 3, 2.55f, std::nullopt};
    lsq.norm = fit::FitNorm::Lsq;
    FitKey minimax = lsq;
    minimax.norm = fit::FitNorm::Minimax;
    EXPECT_NE(lsq.text(), minimax.text());
    // The text of a key before the norm could be chosen (and the server's fits were least squares), so the
    // cache files those fits wrote are found again.
    EXPECT_EQ(lsq.text(), "blobs__e40a33333_d3_b40233333_cells_v00000000");
    EXPECT_EQ(fitOptionsFor(minimax).norm, fit::FitNorm::Minimax);
    EXPECT_EQ(fitOptionsFor(lsq).norm, fit::FitNorm::Lsq);
}

TEST(VotSpaceCache, EvictsLeastRecentlyUsedOverBudget) {
    const FitKey k1{"a", 1.f, 3, 0.f, std::nullopt}, k2{"a", 2.f, 3, 0.f, std::nullopt},
        k3{"a", 3.f, 3, 0.f, std::nullopt};
    const std::size_t one = VotSpaceLru::bytesOf(*spaceWith(100, k1));
    ASSERT_EQ(VotSpaceLru::bytesOf(*spaceWith(100, k3)), one);
    VotSpaceCache cache({}, 2 * one + 10);
    cache.store(k1, spaceWith(100, k1));
    cache.store(k2, spaceWith(100, k2));
    ASSERT_TRUE(cache.findInMemory(k1)); // k1 is now the most recent
    cache.store(k3, spaceWith(100, k3));
    EXPECT_TRUE(cache.findInMemory(k1));
    EXPECT_FALSE(cache.findInMemory(k2));
    EXPECT_TRUE(cache.findInMemory(k3));
}

TEST(VotSpaceCache, LaterWritesReachTheDiskByWaitOrDestruction) {
    test::TempDir dir;
    const FitKey k1{"a", 1.f, 3, 0.f, std::nullopt}, k2{"a", 2.f, 3, 0.f, std::nullopt};
    {
        VotSpaceCache cache(dir.path(), 1 << 20);
        cache.storeOnDiskLater(k1, spaceWith(5, k1));
        cache.waitForDiskWrites();
        EXPECT_EQ(cache.diskEntries().size(), 1u);
        cache.storeOnDiskLater(k2, spaceWith(6, k2)); // left to the destructor
    }
    VotSpaceCache cache(dir.path(), 1 << 20);
    ASSERT_TRUE(cache.find(k2));
    EXPECT_EQ(cache.find(k2)->vots.size(), 6u);
}

TEST(VotSpaceCache, LaterWritesWaitWhileTheServerIsBusy) {
    test::TempDir dir;
    const FitKey k1{"a", 1.f, 3, 0.f, std::nullopt}, k2{"a", 2.f, 3, 0.f, std::nullopt};
    std::atomic<bool> busy{true};
    VotSpaceCache cache(dir.path(), 1 << 20);
    cache.deferDiskWritesWhile([&busy] { return busy.load(); });
    cache.storeOnDiskLater(k1, spaceWith(5, k1));
    std::this_thread::sleep_for(std::chrono::milliseconds(600)); // past the start delay, still busy
    EXPECT_TRUE(cache.diskEntries().empty());
    busy = false;
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (cache.diskEntries().empty() && std::chrono::steady_clock::now() < giveUp)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(cache.diskEntries().size(), 1u);

    busy = true;
    cache.storeOnDiskLater(k2, spaceWith(6, k2));
    cache.waitForDiskWrites(); // does not wait for the server to pause
    EXPECT_EQ(cache.diskEntries().size(), 2u);
}

TEST(VotSpaceCache, WritesWaitingHoldNoMoreThanTheMemoryBudget) {
    test::TempDir dir;
    const FitKey k1{"a", 1.f, 3, 0.f, std::nullopt}, k2{"a", 2.f, 3, 0.f, std::nullopt},
        k3{"a", 3.f, 3, 0.f, std::nullopt};
    const std::size_t one = VotSpaceLru::bytesOf(*spaceWith(100, k1));
    std::atomic<bool> busy{true};
    VotSpaceCache cache(dir.path(), 2 * one + one / 2);
    cache.deferDiskWritesWhile([&busy] { return busy.load(); });
    cache.storeOnDiskLater(k1, spaceWith(100, k1));
    cache.storeOnDiskLater(k2, spaceWith(100, k2));
    EXPECT_EQ(cache.pendingDiskWriteBytes(), 2 * one);
    cache.storeOnDiskLater(k3, spaceWith(100, k3)); // a third would exceed the budget: skipped
    EXPECT_EQ(cache.pendingDiskWriteBytes(), 2 * one);
    busy = false;
    cache.waitForDiskWrites();
    EXPECT_EQ(cache.pendingDiskWriteBytes(), 0u);
    EXPECT_EQ(cache.diskEntries().size(), 2u);
    EXPECT_FALSE(cache.find(k3));

    // One Vot-Space larger than the whole budget is still written when nothing else waits.
    VotSpaceCache small(dir.path(), one / 2);
    small.storeOnDiskLater(k3, spaceWith(100, k3));
    small.waitForDiskWrites();
    EXPECT_TRUE(small.find(k3));
}

TEST(VotSpaceCache, DiskRoundTripAndForeignFilesIgnored) {
    test::TempDir dir;
    const FitKey key{"a", 1.f, 3, 0.f, std::nullopt};
    {
        VotSpaceCache cache(dir.path(), 1 << 20);
        cache.store(key, spaceWith(5, key));
        EXPECT_EQ(cache.diskEntries().size(), 1u);
    }
    VotSpaceCache cache(dir.path(), 1 << 20);
    EXPECT_FALSE(cache.findInMemory(key));
    const auto space = cache.find(key);
    ASSERT_TRUE(space);
    EXPECT_EQ(space->vots.size(), 5u);
    EXPECT_EQ(fitSecondsOf(*space), 1.5);

    // A file under another key's name (copied or renamed) is not trusted.
    const FitKey other{"a", 2.f, 3, 0.f, std::nullopt};
    fit::writeVotSpaceFile((dir.path() / (other.text() + ".vots")).string(), *space);
    EXPECT_FALSE(cache.find(other));
    // A truncated file is ignored too.
    const FitKey third{"a", 3.f, 3, 0.f, std::nullopt};
    dir.write(third.text() + ".vots", "VOTS");
    EXPECT_FALSE(cache.find(third));
}

TEST(VotSpaceStore, KeepsItsFilesWithinTheBudgetLeastRecentlyUsedFirst) {
    namespace fs = std::filesystem;
    const FitKey a{"a", 1.f, 3, 0.f, std::nullopt}, b{"a", 2.f, 3, 0.f, std::nullopt},
        c{"a", 3.f, 3, 0.f, std::nullopt};
    std::uintmax_t fileBytes = 0;
    {
        test::TempDir probe;
        VotSpaceStore unlimited(probe.path(), std::uint64_t{1} << 40);
        unlimited.write(a, *spaceWith(200, a));
        ASSERT_EQ(unlimited.entries().size(), 1u);
        fileBytes = unlimited.entries()[0].bytes;
    }
    ASSERT_GT(fileBytes, 200u * 100);
    test::TempDir dir;
    VotSpaceStore store(dir.path(), fileBytes * 5 / 2); // room for two files of this size
    const auto fileOf = [&](const FitKey& key) { return dir.path() / (key.text() + ".vots"); };
    const auto now = fs::file_time_type::clock::now();
    store.write(a, *spaceWith(200, a));
    fs::last_write_time(fileOf(a), now - std::chrono::seconds(30));
    store.write(b, *spaceWith(200, b));
    fs::last_write_time(fileOf(b), now - std::chrono::seconds(20));
    EXPECT_EQ(store.entries().size(), 2u);
    ASSERT_TRUE(store.read(a)) << "a read makes `a` the most recently used";
    store.write(c, *spaceWith(200, c));
    EXPECT_TRUE(fs::exists(fileOf(a)));
    EXPECT_FALSE(fs::exists(fileOf(b))) << "the least recently used file goes first";
    EXPECT_TRUE(fs::exists(fileOf(c)));
    EXPECT_EQ(store.entries().size(), 2u);

    VotSpaceStore tiny(dir.path(), 0);
    tiny.write(b, *spaceWith(200, b));
    ASSERT_EQ(tiny.entries().size(), 1u) << "over the budget, only the newest file stays";
    EXPECT_TRUE(tiny.read(b));
}

TEST(VotSpaceStore, ACachedFitKeepsItsBackgroundFill) {
    // The server's own fits reach the disk through cacheMetaFor and come back as `vots render` reads files.
    const FitKey key{"a", 1.f, 3, -983.9f, std::nullopt};
    fit::VotSpace space = *spaceWith(3, key);
    space.background = key.background;
    space.backgroundFill = -1000.25f;
    space.metaJson = cacheMetaFor(key, datasetFor(key), fit::FitStats{}, space);
    test::TempDir dir;
    VotSpaceStore store(dir.path(), std::uint64_t{1} << 30);
    store.write(key, space);
    const auto read = store.read(key);
    ASSERT_TRUE(read);
    ASSERT_TRUE(read->backgroundFill);
    EXPECT_EQ(*read->backgroundFill, -1000.25f);
    EXPECT_EQ(read->background, -983.9f);
}

TEST(VotSpaceCache, RemovesTemporariesOfDeadWritersOnStart) {
    // A server killed between open and rename leaves "<key>.vots.tmp-<pid>-<n>" behind.
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) ::_exit(0);
    ASSERT_EQ(::waitpid(child, nullptr, 0), child); // reaped: its pid names no process now
    test::TempDir dir;
    const std::string dead = "a.vots.tmp-" + std::to_string(child) + "-0";
    const std::string live = "b.vots.tmp-" + std::to_string(::getpid()) + "-3";
    for (const std::string& name : {dead, live, std::string("notes.tmp-1-2"), std::string("c.vots")})
        dir.write(name, "half");
    VotSpaceCache cache(dir.path(), 1 << 20);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / dead));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / live)); // a running writer may still rename it
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "notes.tmp-1-2"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "c.vots")); // corrupt files are handled by find()
}

} // namespace
} // namespace vots::server
