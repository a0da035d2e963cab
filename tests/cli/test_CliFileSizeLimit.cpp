// `vots fit` under RLIMIT_FSIZE (a full quota): a one-line "File too large" error and exit 2, not SIGXFSZ
// death.
#include "CliRunner.h"
#include "TempDir.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>

namespace vots::test {
namespace {

/// runVots with a file-size limit set in the child only (posix_spawn cannot set limits).
CliResult runVotsWithFileSizeLimit(const std::vector<std::string>& args, rlim_t limitBytes) {
    TempDir capture;
    const std::string outPath = capture.file("stdout"), errPath = capture.file("stderr");
    CommandLine command(args);
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        const rlimit limit{limitBytes, limitBytes};
        const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 ||
            ::setrlimit(RLIMIT_FSIZE, &limit) != 0)
            ::_exit(127);
        ::execv(VOTS_CLI_BINARY, command.argv.data());
        ::_exit(127);
    }
    return collectResult(pid, outPath, errPath);
}

TEST(CliFileSizeLimit, FitReportsFileTooLargeAndLeavesNothing) {
    TempDir dir;
    const std::string out = dir.file("head.vots");
    const std::vector<std::string> args{
        "fit", std::string(VOTS_TEST_DATA_DIR) + "/mri-brain_33x41x25_int16.nii", "-o", out, "--eps", "5%"};
    const CliResult r = runVotsWithFileSizeLimit(args, 1024); // the file needs tens of KiB
    const std::string what = describe(args, r);
    EXPECT_EQ(r.exitCode, 2) << what; // -1 would mean killed by SIGXFSZ
    ASSERT_EQ(r.errLines().size(), 1u) << what;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << what;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << what; // neither the file nor a temporary
}

} // namespace
} // namespace vots::test
