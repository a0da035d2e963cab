// ClientQuota: how many requests of one kind each client (remote address) may have in progress, so
// that one client flooding the server is refused (429) while the others keep their place.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>
#include <string>

namespace vots::server {

/// Thread-safe.
class ClientQuota {
public:
    /// perClient: in progress at once per client; 0 or less: unlimited. what: named in the 429 message.
    ClientQuota(int perClient, std::string what) : mPerClient(perClient), mWhat(std::move(what)) {}
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

    /// A place for the client, or HttpError 429 when it already has perClient in progress.
    Ticket enter(const std::string& client);
    /// In progress for the client now.
    int inProgress(const std::string& client) const;
    int perClient() const { return mPerClient; }

private:
    void leave(const std::string& client);

    const int mPerClient;
    const std::string mWhat;
    mutable std::mutex mMutex;
    std::map<std::string, int> mCounts; // only clients with something in progress
};

} // namespace vots::server
