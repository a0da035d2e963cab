// ClientQuota: how many requests of one kind each client (remote address) may have in progress, and how
// many more may wait their turn in order, so that one client flooding the server is refused (429) while
// the others keep their place, and the several users behind one address are queued, not refused.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <string>

namespace vots::server {

/// Thread-safe.
class ClientQuota {
public:
    /// perClient: in progress at once per client; 0 or less: unlimited. queuedPerClient: more that wait
    /// for a place, first come first served, at most maxWait each. what: named in the 429 message.
    ClientQuota(int perClient, std::string what, int queuedPerClient = 0,
                std::chrono::milliseconds maxWait = std::chrono::seconds(60))
        : mPerClient(perClient), mQueuedPerClient(queuedPerClient), mMaxWait(maxWait),
          mWhat(std::move(what)) {}
    ClientQuota(const ClientQuota&) = delete;
    ClientQuota& operator=(const ClientQuota&) = delete;

    /// Holds one place of a client while it lives.
    class Ticket {
    public:
        Ticket() = default;
        Ticket(Ticket&& other) noexcept : mQuota(other.mQuota), mClient(std::move(other.mClient)) {
            other.mQuota = nullptr;
        }
        Ticket& operator=(Ticket&& other) noexcept;
        ~Ticket() { release(); }
        void release();

    private:
        friend class ClientQuota;
        Ticket(ClientQuota* quota, std::string client) : mQuota(quota), mClient(std::move(client)) {}
        ClientQuota* mQuota = nullptr;
        std::string mClient;
    };

    /// A place for the client: at once, or after its earlier requests waiting for one (at most
    /// queuedPerClient wait). HttpError 429 when that many wait already, 503 after waiting maxWait.
    Ticket enter(const std::string& client);
    /// In progress for the client now.
    int inProgress(const std::string& client) const;
    int perClient() const { return mPerClient; }

private:
    void leave(const std::string& client);

    struct Places {
        int inProgress = 0;
        std::deque<std::uint64_t> waiting; // the waiters' numbers, in the order they came
    };

    const int mPerClient;
    const int mQueuedPerClient;
    const std::chrono::milliseconds mMaxWait;
    const std::string mWhat;
    mutable std::mutex mMutex;
    std::condition_variable mFreed;
    std::map<std::string, Places> mClients; // only clients with something in progress or waiting
    std::uint64_t mWaiters = 0;             // numbers given to waiters so far
};

} // namespace vots::server
