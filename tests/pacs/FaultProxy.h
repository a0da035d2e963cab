// tests/pacs/fault_proxy.py in front of the fixture's Orthanc for one test scope: logs each request line
// and strikes with the faults it is given.
#pragma once

#include "OrthancState.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace vots::test {

inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FaultProxy {
public:
    /// `faults`: fault_proxy.py's options (e.g. {"--refuse-store"}); none passes everything unchanged.
    explicit FaultProxy(const std::filesystem::path& folder, const std::vector<std::string>& faults = {})
        : mLog(folder / "proxy.log") {
        const std::string portFile = (folder / "proxy_port").string();
        std::vector<std::string> args = {
            "python3",     VOTS_FAULT_PROXY, "--target", orthancStateFile("port"),
            "--port-file", portFile,         "--log",    mLog.string()};
        args.insert(args.end(), faults.begin(), faults.end());
        std::vector<char*> argv;
        for (std::string& a : args)
            argv.push_back(a.data());
        argv.push_back(nullptr);
        if (posix_spawnp(&mPid, "python3", nullptr, nullptr, argv.data(), environ) != 0)
            throw std::runtime_error("cannot start the fault proxy");
        for (int i = 0; i < 200 && !std::filesystem::exists(portFile); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        mPort = readText(portFile);
        if (mPort.empty()) throw std::runtime_error("the fault proxy wrote no port");
    }
    ~FaultProxy() {
        kill(mPid, SIGTERM);
        waitpid(mPid, nullptr, 0);
    }
    FaultProxy(const FaultProxy&) = delete;
    FaultProxy& operator=(const FaultProxy&) = delete;

    std::string port() const { return mPort; }
    std::string log() const { return readText(mLog); }
    /// Request lines that asked for the series' instances (a retrieve), not its metadata.
    int seriesRetrieves(const std::string& seriesUid) const {
        const std::string log = readText(mLog);
        const std::string line = "/series/" + seriesUid + " HTTP/1.1";
        int count = 0;
        for (auto at = log.find(line); at != std::string::npos; at = log.find(line, at + 1))
            ++count;
        return count;
    }

private:
    std::filesystem::path mLog;
    pid_t mPid = -1;
    std::string mPort;
};

} // namespace vots::test
