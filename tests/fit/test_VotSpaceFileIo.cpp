// Vot-Space file I/O: atomic write, no leftovers on failure, an existing file survives a failed write.
#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"

#include "TempDir.h"
#include "VotSpaceBytes.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

namespace vots::fit {
namespace {

namespace fs = std::filesystem;
using test::Bytes;
using test::makeSampleSpace;
using test::TempDir;

Bytes slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

void dump(const std::string& path, const Bytes& b) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

std::size_t entryCount(const fs::path& dir) {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

/// Runs `body` and returns the InputError message it throws ("" when it does not throw).
template <class F> std::string errorOf(F&& body) {
    try {
        body();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(VotSpaceFileIo, ALargeWritePausesBetweenMebibytesAndStaysExact) {
    TempDir dir;
    const std::string path = dir.file("big.vots");
    const VotSpace s = makeSampleSpace(40000); // several MiB of records
    const std::size_t bytes = encodeVotSpace(s).size();
    ASSERT_GT(bytes, std::size_t{3} << 20);
    std::size_t pauses = 0;
    writeVotSpaceFile(path, s, [&pauses] { ++pauses; });
    EXPECT_EQ(pauses, (bytes - 1) >> 20) << "one pause between consecutive MiB, none after the last";
    EXPECT_EQ(slurp(path), encodeVotSpace(s));
    EXPECT_EQ(entryCount(dir.path()), 1u);
}

TEST(VotSpaceFileIo, WriteThenReadLeavesOnlyTheFile) {
    TempDir dir;
    const std::string path = dir.file("a.vots");
    const VotSpace s = makeSampleSpace(4);
    writeVotSpaceFile(path, s);
    EXPECT_EQ(slurp(path), encodeVotSpace(s));
    EXPECT_EQ(encodeVotSpace(readVotSpaceFileWithoutMeta(path)), encodeVotSpace(s));
    EXPECT_EQ(entryCount(dir.path()), 1u); // no temp file left behind
    // Overwriting an existing file replaces it.
    writeVotSpaceFile(path, makeSampleSpace(1));
    EXPECT_EQ(readVotSpaceFileWithoutMeta(path).vots.size(), 1u);
    EXPECT_EQ(entryCount(dir.path()), 1u);
}

TEST(VotSpaceFileIo, WriteIntoMissingFolderThrowsAndCreatesNothing) {
    TempDir dir;
    const std::string path = dir.file("missing/sub/a.vots");
    const std::string msg = errorOf([&] { writeVotSpaceFile(path, makeSampleSpace()); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
    EXPECT_EQ(entryCount(dir.path()), 0u);
}

TEST(VotSpaceFileIo, WriteBelowARegularFileThrows) {
    TempDir dir;
    dump(dir.file("plain"), {1, 2, 3});
    const std::string msg = errorOf([&] { writeVotSpaceFile(dir.file("plain/a.vots"), makeSampleSpace()); });
    EXPECT_NE(msg.find("Not a directory"), std::string::npos) << msg;
    EXPECT_EQ(entryCount(dir.path()), 1u);
}

// Root ignores folder permissions, and CI runs as root: there the write runs as the unprivileged user
// `nobody`, whom they bind. Only the effective user changes, so the test can take root back afterwards.
class AsUnprivilegedUser {
public:
    AsUnprivilegedUser() {
        if (::geteuid() != 0) return;
        if (::seteuid(NOBODY) != 0) throw std::runtime_error("seteuid(nobody) failed");
        mSwitched = true;
    }
    ~AsUnprivilegedUser() {
        if (mSwitched && ::seteuid(0) != 0) std::abort(); // the rest of the run would not be root's
    }
    AsUnprivilegedUser(const AsUnprivilegedUser&) = delete;
    AsUnprivilegedUser& operator=(const AsUnprivilegedUser&) = delete;

private:
    static constexpr uid_t NOBODY = 65534;
    bool mSwitched = false;
};

TEST(VotSpaceFileIo, WriteIntoReadOnlyFolderThrows) {
    TempDir dir;
    const auto readAndEnter = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                              fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec;
    // Anyone may reach the folder; nobody but its owner could write into the temporary folder itself.
    fs::permissions(dir.path(), readAndEnter | fs::perms::owner_write);
    fs::create_directory(dir.path() / "ro");
    fs::permissions(dir.path() / "ro", readAndEnter);
    std::string msg;
    {
        const AsUnprivilegedUser unprivileged;
        msg = errorOf([&] { writeVotSpaceFile(dir.file("ro/a.vots"), makeSampleSpace()); });
    }
    fs::permissions(dir.path() / "ro", fs::perms::owner_all);
    EXPECT_NE(msg.find("Permission denied"), std::string::npos) << msg;
    EXPECT_EQ(entryCount(dir.path() / "ro"), 0u);
}

TEST(VotSpaceFileIo, FailedRenameRemovesTheTempFile) {
    TempDir dir;
    fs::create_directories(dir.path() / "target" / "child"); // rename(file, non-empty folder) fails
    const std::string msg = errorOf([&] { writeVotSpaceFile(dir.file("target"), makeSampleSpace()); });
    EXPECT_NE(msg.find("cannot write"), std::string::npos) << msg;
    EXPECT_EQ(entryCount(dir.path()), 1u);
    EXPECT_TRUE(fs::is_directory(dir.path() / "target" / "child"));
}

TEST(VotSpaceFileIo, InvalidSpaceLeavesExistingFileIntact) {
    TempDir dir;
    const std::string path = dir.file("a.vots");
    writeVotSpaceFile(path, makeSampleSpace(2));
    const Bytes before = slurp(path);
    VotSpace bad = makeSampleSpace(2);
    bad.vots[1].c[0] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(writeVotSpaceFile(path, bad), InputError);
    EXPECT_EQ(slurp(path), before);
    EXPECT_EQ(entryCount(dir.path()), 1u);
}

TEST(VotSpaceFileIo, DiskFullMidWriteLeavesExistingFileIntact) {
    TempDir dir;
    const std::string path = dir.file("a.vots");
    writeVotSpaceFile(path, makeSampleSpace(2));
    const Bytes before = slurp(path);

    // A file-size limit makes write(2) fail with EFBIG part way, like a full disk.
    rlimit old{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
    const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit small = old;
    small.rlim_cur = 4096;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    const std::string msg = errorOf([&] { writeVotSpaceFile(path, makeSampleSpace(200)); });
    ::setrlimit(RLIMIT_FSIZE, &old);
    std::signal(SIGXFSZ, oldHandler);

    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_EQ(slurp(path), before);
    EXPECT_EQ(entryCount(dir.path()), 1u);
}

TEST(VotSpaceFileIo, ReadErrorsNameThePath) {
    TempDir dir;
    const std::string missing = dir.file("nope.vots");
    std::string msg = errorOf([&] { readVotSpaceFileWithoutMeta(missing); });
    EXPECT_NE(msg.find(missing), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;

    msg = errorOf([&] { readVotSpaceFileWithoutMeta(dir.path().string()); });
    EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;

    const std::string truncated = dir.file("t.vots");
    Bytes b = encodeVotSpace(makeSampleSpace(3));
    b.resize(b.size() / 2); // cut mid-record
    dump(truncated, b);
    msg = errorOf([&] { readVotSpaceFileWithoutMeta(truncated); });
    EXPECT_NE(msg.find(truncated), std::string::npos) << msg;
    EXPECT_NE(msg.find("does not match"), std::string::npos) << msg;
}

} // namespace
} // namespace vots::fit
