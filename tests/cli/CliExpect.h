// GoogleTest checks on a finished `vots` run, shared by the CLI tests.
#pragma once

#include "CliRunner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <string>
#include <vector>

namespace vots::test {

/// A bad command: exit code 2, exactly one stderr line that starts "vots: error:" and contains
/// `needle`, nothing on stdout, and the folder unchanged (no output, no temp files).
inline void expectBadInput(const TempDir& dir, const std::vector<std::string>& args,
                           const std::string& needle) {
    const auto before = std::distance(std::filesystem::directory_iterator(dir.path()), {});
    const CliResult r = runVots(args);
    const std::string what = describe(args, r);
    EXPECT_EQ(r.exitCode, 2) << what;
    const auto lines = r.errLines();
    ASSERT_EQ(lines.size(), 1u) << what;
    EXPECT_EQ(lines[0].rfind("vots: error: ", 0), 0u) << what;
    EXPECT_NE(lines[0].find(needle), std::string::npos) << "expected '" << needle << "' in: " << what;
    EXPECT_EQ(r.out, "") << what;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), before) << what;
}

} // namespace vots::test
