// The real Vots server on a free 127.0.0.1 port for one test scope: listens on a thread, stops at scope exit.
#pragma once

#include "vots/server/Server.h"

#include <httplib.h>

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

namespace vots::test {

class LoopbackServer {
public:
    /// bindHost: where it listens ("0.0.0.0" for the rules of an exposed server); clients use 127.0.0.1.
    explicit LoopbackServer(server::ServerOptions options, const std::string& bindHost = "127.0.0.1")
        : mServer(std::make_unique<server::Server>(std::move(options))) {
        mPort = mServer->bindToAnyPort(bindHost);
        if (mPort < 0) throw std::runtime_error("cannot bind a loopback port");
        mThread = std::thread([this] { mServer->listenAfterBind(); });
        // httplib 0.11.4 has no wait_until_ready: poll until the accept loop runs.
        for (int i = 0; i < 1000 && !mServer->isRunning(); ++i)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (!mServer->isRunning()) throw std::runtime_error("loopback server did not start");
    }
    ~LoopbackServer() {
        mServer->stop();
        mThread.join();
    }
    LoopbackServer(const LoopbackServer&) = delete;
    LoopbackServer& operator=(const LoopbackServer&) = delete;

    int port() const { return mPort; }
    server::Server& server() { return *mServer; }

    /// A fresh client with generous timeouts (fits and llvmpipe frames can take seconds).
    std::unique_ptr<httplib::Client> client() const {
        auto c = std::make_unique<httplib::Client>("127.0.0.1", mPort);
        c->set_connection_timeout(10);
        c->set_read_timeout(300);
        c->set_write_timeout(60);
        return c;
    }

private:
    std::unique_ptr<server::Server> mServer;
    int mPort = -1;
    std::thread mThread;
};

} // namespace vots::test
