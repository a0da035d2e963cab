// ConnectionGate on its own: a request is handed on only once it has arrived; idle, slow and oversized
// ones are closed or refused without ever reaching the handler.
#include "connection/ConnectionGate.h"

#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {
namespace {

using namespace std::chrono_literals;

/// A gate with short limits, a socket pair per connection, and the requests it dispatched.
class GateTest : public ::testing::Test {
protected:
    GateTest() {
        GateLimits limits;
        limits.firstByte = 300ms;
        limits.wholeRequest = 800ms;
        limits.maxHeaderLines = 10;
        limits.maxBodyBytes = 100;
        mGate = std::make_unique<ConnectionGate>(limits, [this](ArrivedRequest r) {
            std::lock_guard lock(mMutex);
            mArrived.push_back(std::move(r));
            mChanged.notify_all();
        });
    }
    ~GateTest() override {
        mGate->stop();
        for (const ArrivedRequest& r : mArrived)
            ::close(r.fd);
        for (const int fd : mClients)
            ::close(fd);
    }

    /// The client end of a new connection the gate holds.
    int connect() {
        int pair[2];
        EXPECT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, pair), 0);
        mGate->add(pair[1]);
        mClients.push_back(pair[0]);
        return pair[0];
    }
    static void send(int fd, const std::string& bytes) {
        ASSERT_EQ(::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size()));
    }
    std::size_t arrivedWithin(std::chrono::milliseconds wait, std::size_t count) {
        std::unique_lock lock(mMutex);
        mChanged.wait_for(lock, wait, [&] { return mArrived.size() >= count; });
        return mArrived.size();
    }
    /// What the gate sent before it closed the client's connection; "timeout" when it stays open.
    static std::string readUntilClosed(int fd, std::chrono::milliseconds wait) {
        std::string all;
        char buffer[4096];
        for (;;) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(wait.count())) <= 0) return all + "timeout";
            const ssize_t n = ::recv(fd, buffer, sizeof buffer, 0);
            if (n <= 0) return all;
            all.append(buffer, static_cast<std::size_t>(n));
        }
    }

    std::unique_ptr<ConnectionGate> mGate;
    std::mutex mMutex;
    std::condition_variable mChanged;
    std::vector<ArrivedRequest> mArrived;
    std::vector<int> mClients;
};

TEST_F(GateTest, ARequestArrivingInPiecesIsHandedOnWhole) {
    const int fd = connect();
    send(fd, "GET /api/data");
    std::this_thread::sleep_for(50ms);
    send(fd, "sets?x=1 HTTP/1.1\r\nHost: a\r\n");
    EXPECT_EQ(arrivedWithin(100ms, 1), 0u) << "dispatched before the head ended";
    send(fd, "\r\n");
    ASSERT_EQ(arrivedWithin(2s, 1), 1u);
    EXPECT_EQ(mArrived[0].method, "GET");
    EXPECT_EQ(mArrived[0].target, "/api/datasets?x=1");
    EXPECT_EQ(mArrived[0].bytes, "GET /api/datasets?x=1 HTTP/1.1\r\nHost: a\r\n\r\n");
}

TEST_F(GateTest, ABodyWithinTheLimitIsWaitedFor) {
    const int fd = connect();
    send(fd, "POST /api/fit HTTP/1.1\r\nContent-Length: 10\r\n\r\n12345");
    EXPECT_EQ(arrivedWithin(150ms, 1), 0u);
    send(fd, "67890");
    ASSERT_EQ(arrivedWithin(2s, 1), 1u);
    EXPECT_EQ(mArrived[0].bytes.substr(mArrived[0].bytes.size() - 10), "1234567890");
}

TEST_F(GateTest, ABodyAboveTheLimitIsHandedOnAfterTheHead) {
    const int fd = connect();
    send(fd, "POST /api/fit HTTP/1.1\r\nContent-Length: 1000\r\n\r\n");
    EXPECT_EQ(arrivedWithin(2s, 1), 1u) << "the handler answers 413";
}

TEST_F(GateTest, AChunkedBodyIs411JsonAndNeverHandedOn) {
    const int fd = connect();
    // A client that would trickle chunks would hold a worker while it reads them.
    send(fd, "POST /api/fit HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n5\r\n{\"a\":\r\n");
    const std::string answer = readUntilClosed(fd, 4s);
    EXPECT_EQ(answer.substr(0, 12), "HTTP/1.1 411");
    EXPECT_NE(answer.find("{\"error\":"), std::string::npos);
    EXPECT_EQ(arrivedWithin(0ms, 1), 0u);
}

TEST_F(GateTest, ExpectContinueIsAnsweredByTheGateWhichThenWaitsForTheBody) {
    const int fd = connect();
    send(fd, "POST /api/fit HTTP/1.1\r\nExpect: 100-continue\r\nContent-Length: 5\r\nHost: x\r\n\r\n");
    char buffer[64] = {};
    pollfd p{fd, POLLIN, 0};
    ASSERT_EQ(::poll(&p, 1, 2000), 1);
    const ssize_t n = ::recv(fd, buffer, sizeof buffer - 1, 0);
    EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0), "HTTP/1.1 100 Continue\r\n\r\n");
    EXPECT_EQ(arrivedWithin(150ms, 1), 0u) << "no worker before the body";
    send(fd, "12345");
    ASSERT_EQ(arrivedWithin(2s, 1), 1u);
    // Handed on without its Expect line, so the handler does not say 100 again.
    EXPECT_EQ(mArrived[0].bytes, "POST /api/fit HTTP/1.1\r\nContent-Length: 5\r\nHost: x\r\n\r\n12345");
}

TEST_F(GateTest, AnIdleConnectionIsClosedUnhandled) {
    const int fd = connect();
    EXPECT_EQ(readUntilClosed(fd, 3s), "");
    EXPECT_EQ(arrivedWithin(0ms, 1), 0u);
    EXPECT_EQ(mGate->waiting(), 0u);
}

TEST_F(GateTest, ASlowSenderIsClosedAtTheRequestDeadline) {
    const int fd = connect();
    const auto start = std::chrono::steady_clock::now();
    std::string answer;
    for (int i = 0; i < 20 && answer.empty(); ++i) { // a byte every 100 ms: never idle, never done
        [[maybe_unused]] const ssize_t n = ::send(fd, "G", 1, MSG_NOSIGNAL); // fails once closed
        answer = readUntilClosed(fd, 100ms);
        if (answer == "timeout")
            answer.clear();
        else
            break;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, 1500ms);
    EXPECT_EQ(arrivedWithin(0ms, 1), 0u);
}

TEST_F(GateTest, TooManyHeaderLinesAre431Json) {
    const int fd = connect();
    std::string head = "GET / HTTP/1.1\r\n";
    for (int i = 0; i < 20; ++i)
        head += "X-" + std::to_string(i) + ": y\r\n";
    send(fd, head + "\r\n");
    const std::string answer = readUntilClosed(fd, 3s);
    EXPECT_EQ(answer.substr(0, 12), "HTTP/1.1 431");
    EXPECT_NE(answer.find("Content-Type: application/json"), std::string::npos);
    EXPECT_NE(answer.find("{\"error\":"), std::string::npos);
    EXPECT_EQ(arrivedWithin(0ms, 1), 0u);
}

TEST_F(GateTest, ATooLongRequestLineIs414BeforeItEnds) {
    const int fd = connect();
    send(fd, "GET /" + std::string(9000, 'a'));
    const std::string answer = readUntilClosed(fd, 3s);
    EXPECT_EQ(answer.substr(0, 12), "HTTP/1.1 414");
    EXPECT_EQ(arrivedWithin(0ms, 1), 0u);
}

TEST_F(GateTest, ARequestThenAHalfCloseIsStillHandedOn) {
    const int fd = connect();
    send(fd, "GET / HTTP/1.1\r\n\r\n");
    ::shutdown(fd, SHUT_WR);
    EXPECT_EQ(arrivedWithin(2s, 1), 1u);
}

} // namespace
} // namespace vots::server
