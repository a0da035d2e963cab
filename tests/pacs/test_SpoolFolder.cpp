// The retrieve's spool folder: private, removed with its contents, or kept under another name on request.
#include "TempDir.h"

#include "vots/fit/Error.h"
#include "vots/pacs/SpoolFolder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace {

namespace fs = std::filesystem;
using vots::pacs::SpoolFolder;

TEST(SpoolFolder, IsPrivateAndGoesWithItsContents) {
    vots::test::TempDir parent;
    std::string path;
    {
        const SpoolFolder spool(parent.path().string());
        path = spool.path();
        EXPECT_EQ(fs::path(path).parent_path(), parent.path());
        EXPECT_EQ(fs::status(path).permissions() & fs::perms::all, fs::perms::owner_all);
        std::ofstream(path + "/instance.dcm") << "bytes";
        fs::create_directory(path + "/sub");
    }
    EXPECT_FALSE(fs::exists(path));
    EXPECT_TRUE(fs::is_empty(parent.path()));
}

TEST(SpoolFolder, MovesWithItsOwnerAndIsRemovedOnce) {
    vots::test::TempDir parent;
    SpoolFolder first(parent.path().string());
    const std::string path = first.path();
    SpoolFolder second = std::move(first);
    EXPECT_EQ(second.path(), path);
    EXPECT_TRUE(first.path().empty()); // a moved-from spool is empty by contract, so it removes nothing
    EXPECT_TRUE(fs::exists(path));
}

TEST(SpoolFolder, KeptFolderOutlivesItsObject) {
    vots::test::TempDir parent;
    const std::string kept = parent.file("series-1.2.3");
    {
        SpoolFolder spool(parent.path().string());
        std::ofstream(spool.path() + "/instance.dcm") << "bytes";
        spool.keepAs(kept);
        EXPECT_TRUE(spool.path().empty());
        SpoolFolder other(parent.path().string());
        EXPECT_THROW(other.keepAs(kept), vots::fit::InputError); // it exists
    }
    EXPECT_TRUE(fs::exists(kept + "/instance.dcm"));
    EXPECT_EQ(std::distance(fs::directory_iterator(parent.path()), fs::directory_iterator()), 1);
}

} // namespace
