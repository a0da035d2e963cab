// Runs the real `vots` binary as a child process and captures exit code, stdout and stderr.
#pragma once

#include "TempDir.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cerrno>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace vots::test {

struct CliResult {
    int exitCode = -1;       // -1: killed by a signal
    long peakResidentKb = 0; // of `vots` and the children it waited for (its DICOM readers)
    std::string out;
    std::string err;

    /// stderr split into lines (without the newlines).
    std::vector<std::string> errLines() const {
        std::vector<std::string> lines;
        std::istringstream in(err);
        for (std::string line; std::getline(in, line);)
            lines.push_back(line);
        return lines;
    }
};

inline std::string slurpText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// VOTS_CLI_BINARY followed by args, owned here, with the NULL-terminated argv exec needs.
struct CommandLine {
    std::vector<std::string> words;
    std::vector<char*> argv;

    explicit CommandLine(const std::vector<std::string>& args) : words{VOTS_CLI_BINARY} {
        words.insert(words.end(), args.begin(), args.end());
        for (std::string& w : words)
            argv.push_back(w.data());
        argv.push_back(nullptr);
    }
    CommandLine(const CommandLine&) = delete; // argv points into words
    CommandLine& operator=(const CommandLine&) = delete;
};

/// Waits for the child and reads what it wrote to the capture files.
inline CliResult collectResult(pid_t pid, const std::string& outPath, const std::string& errPath) {
    int status = 0;
    rusage usage{};
    while (wait4(pid, &status, 0, &usage) < 0)
        if (errno != EINTR) throw std::runtime_error("waitpid failed");
    CliResult r;
    r.peakResidentKb = usage.ru_maxrss;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurpText(outPath);
    r.err = slurpText(errPath);
    return r;
}

/// Runs VOTS_CLI_BINARY with `args`; output goes through files so a chatty child can never block.
inline CliResult runVots(const std::vector<std::string>& args) {
    TempDir capture;
    const std::string outPath = capture.file("stdout"), errPath = capture.file("stderr");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);

    CommandLine command(args);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, VOTS_CLI_BINARY, &actions, nullptr, command.argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error(std::string("cannot start ") + VOTS_CLI_BINARY);
    return collectResult(pid, outPath, errPath);
}

/// For failure messages: the command line and what it printed.
inline std::string describe(const std::vector<std::string>& args, const CliResult& r) {
    std::string s = "vots";
    for (const std::string& a : args)
        s += " " + a;
    return s + "\n  exit " + std::to_string(r.exitCode) + "\n  stdout: " + r.out + "\n  stderr: " + r.err;
}

} // namespace vots::test
