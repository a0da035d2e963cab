// `vots serve` as a child process for the tests of the command itself: its port, output and exit code.
#pragma once

#include "ServerFixture.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fstream>
#include <iterator>
#include <regex>

extern char** environ;

namespace vots::test {

inline std::string readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// `vots serve --port 0 ...` over the world's folders, output captured in files; SIGTERM at stop().
class ServeProcess {
public:
    /// warmUps: leave out --no-warm-up, for the command's own default.
    ServeProcess(const ServerWorld& world, std::vector<std::string> extra, bool warmUps = false)
        : mOut(world.dir().file("serve.out")), mErr(world.dir().file("serve.err")) {
        std::vector<std::string> words{VOTS_CLI,      "serve",
                                       "--port",      "0",
                                       "--data",      world.data().string(),
                                       "--web",       world.web().string(),
                                       "--cache-dir", world.cache().string(),
                                       "--prepare",   ""};
        if (!warmUps) words.emplace_back("--no-warm-up");
        words.insert(words.end(), extra.begin(), extra.end());
        std::vector<char*> argv;
        for (std::string& w : words)
            argv.push_back(w.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&actions, 1, mOut.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&actions, 2, mErr.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int rc = posix_spawn(&mPid, VOTS_CLI, &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        if (rc != 0) throw std::runtime_error("cannot start vots serve");
        static const std::regex listening(R"(listening on https?://[^ ]*:(\d+)/)");
        for (int i = 0; i < 1200 && mPort < 0 && running(); ++i) {
            std::smatch m;
            const std::string out = readWholeFile(mOut);
            if (std::regex_search(out, m, listening) && out.find("renderer") != std::string::npos)
                mPort = std::stoi(m[1].str());
            else
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    }
    ~ServeProcess() { stop(); }

    int port() const { return mPort; }
    std::unique_ptr<httplib::Client> client() const {
        auto c = std::make_unique<httplib::Client>("127.0.0.1", mPort);
        c->set_read_timeout(60);
        return c;
    }
    /// Stops it (SIGTERM) and returns its exit code; stdout and stderr are complete afterwards. One that
    /// has not ended a minute later fails the test and is killed: a hang costs a minute, not ctest's limit.
    int stop() {
        if (mPid <= 0) return mExit;
        ::kill(mPid, SIGTERM);
        for (int i = 0; i < 1200 && running(); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        if (mPid > 0) {
            ADD_FAILURE() << "vots serve did not stop within a minute of SIGTERM; it wrote:\n" << output();
            ::kill(mPid, SIGKILL);
            ::waitpid(mPid, nullptr, 0);
            mPid = -1;
            mExit = -1;
        }
        return mExit;
    }
    /// Sends it a signal (SIGHUP: read the TLS files again).
    void signal(int number) const {
        if (mPid > 0) ::kill(mPid, number);
    }
    std::string output() const { return readWholeFile(mOut) + readWholeFile(mErr); }
    std::string err() const { return readWholeFile(mErr); }

private:
    bool running() {
        int status = 0;
        if (::waitpid(mPid, &status, WNOHANG) == 0) return true;
        mExit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        mPid = -1;
        return false;
    }

    std::string mOut, mErr;
    pid_t mPid = -1;
    int mPort = -1;
    int mExit = -1;
};

} // namespace vots::test
