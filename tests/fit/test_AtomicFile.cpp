// The one atomic writer: concurrent writers of one path in one process, and failures that keep the old file.
#include "vots/fit/AtomicFile.h"
#include "vots/fit/Error.h"

#include "TempDir.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace vots::fit {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

Bytes slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    return names;
}

TEST(AtomicFile, TemporaryNamesAreUniqueWithinAProcess) {
    std::set<std::string> names;
    for (int i = 0; i < 100; ++i)
        names.insert(uniqueTemporaryPath("/x/a.png"));
    EXPECT_EQ(names.size(), 100u);
}

TEST(AtomicFile, TwoWritersOfOnePathInOneProcessEachLeaveAWholeFile) {
    const test::TempDir dir;
    const std::string path = dir.file("frame.png");
    // Different lengths too: a mix of two writes would show as a wrong size or a foreign byte.
    const Bytes a(3 << 20, 0xAA), b(2 << 20, 0xBB);
    constexpr int WRITES = 20;
    std::vector<std::string> errors(2);
    auto writer = [&](const Bytes& bytes, std::string& error) {
        try {
            for (int i = 0; i < WRITES; ++i)
                writeFileAtomically(path, bytes, [] { std::this_thread::yield(); }); // interleave the pieces
        } catch (const std::exception& e) {
            error = e.what();
        }
    };
    std::thread first(writer, std::cref(a), std::ref(errors[0]));
    std::thread second(writer, std::cref(b), std::ref(errors[1]));
    first.join();
    second.join();
    EXPECT_EQ(errors[0], "");
    EXPECT_EQ(errors[1], "");
    const Bytes last = slurp(path);
    EXPECT_TRUE(last == a || last == b) << "a file of " << last.size() << " bytes that neither writer wrote";
    EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"frame.png"}) << "a temporary was left behind";
}

TEST(AtomicFile, AWriteThatFailsHalfwayLeavesTheOldFileAndNoTemporary) {
    const test::TempDir dir;
    const std::string path = dir.file("frame.png");
    const Bytes old(1000, 0x11);
    writeFileAtomically(path, old);
    const Bytes next(3 << 20, 0x22); // three 1 MiB pieces: the failure comes after the first
    EXPECT_THROW(writeFileAtomically(path, next, [] { throw std::runtime_error("stopped"); }),
                 std::runtime_error);
    EXPECT_EQ(slurp(path), old);
    EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"frame.png"});
}

TEST(AtomicFile, AFailedRenameLeavesTheOldTargetAndNoTemporary) {
    const test::TempDir dir;
    fs::create_directories(dir.path() / "target" / "child"); // rename(file, non-empty folder) fails
    try {
        writeFileAtomically(dir.file("target"), Bytes(10, 1));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cannot write '" + dir.file("target") + "'"), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"target"});
    EXPECT_TRUE(fs::is_directory(dir.path() / "target" / "child"));
}

TEST(AtomicFile, AStagedTemporaryIsPublishedUnderItsPath) {
    const test::TempDir dir;
    const std::string path = dir.file("0001.png");
    const std::string temporary = writeTemporaryFor(path, Bytes(5, 7));
    EXPECT_FALSE(fs::exists(path));
    EXPECT_EQ(slurp(temporary), Bytes(5, 7));
    publishTemporary(temporary, path);
    EXPECT_EQ(slurp(path), Bytes(5, 7));
    EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"0001.png"});
}

} // namespace
} // namespace vots::fit
