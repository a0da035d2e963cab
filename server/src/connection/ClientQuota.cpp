// ClientQuota: per-client counters, entered and left by tickets.
#include "connection/ClientQuota.h"

#include "HttpError.h"

namespace vots::server {

ClientQuota::Ticket& ClientQuota::Ticket::operator=(Ticket&& other) noexcept {
    if (this != &other) {
        release();
        mQuota = other.mQuota;
        mClient = std::move(other.mClient);
        other.mQuota = nullptr;
    }
    return *this;
}

void ClientQuota::Ticket::release() {
    if (mQuota) mQuota->leave(mClient);
    mQuota = nullptr;
}

ClientQuota::Ticket ClientQuota::enter(const std::string& client) {
    if (mPerClient <= 0) return {};
    std::unique_lock lock(mMutex);
    Places& places = mClients[client]; // a map node: it stays put while this waits
    if (places.inProgress < mPerClient && places.waiting.empty()) {
        ++places.inProgress;
        return Ticket(this, client);
    }
    // Counted together: between a place freed and its waiter waking, the one that freed it may ask again.
    if (places.inProgress + static_cast<int>(places.waiting.size()) >= mPerClient + mQueuedPerClient)
        throw HttpError(429, "too many " + mWhat + " in progress from " + client + " (at most " +
                                 std::to_string(mPerClient) + " per client, and " +
                                 std::to_string(mQueuedPerClient) +
                                 " waiting); try again when one has finished");
    const std::uint64_t number = ++mWaiters;
    places.waiting.push_back(number);
    const bool myTurn = mFreed.wait_for(
        lock, mMaxWait, [&] { return places.inProgress < mPerClient && places.waiting.front() == number; });
    std::erase(places.waiting, number);
    if (!myTurn) {
        if (places.inProgress <= 0 && places.waiting.empty()) mClients.erase(client);
        mFreed.notify_all(); // the next waiter may be first now
        throw HttpError(503,
                        "waited too long for one of " + client + "'s " + mWhat + " to finish; try again");
    }
    ++places.inProgress;
    return Ticket(this, client);
}

int ClientQuota::inProgress(const std::string& client) const {
    std::lock_guard lock(mMutex);
    const auto it = mClients.find(client);
    return it == mClients.end() ? 0 : it->second.inProgress;
}

void ClientQuota::leave(const std::string& client) {
    {
        std::lock_guard lock(mMutex);
        const auto it = mClients.find(client);
        if (it == mClients.end()) return;
        --it->second.inProgress;
        if (it->second.inProgress <= 0 && it->second.waiting.empty()) mClients.erase(it);
    }
    mFreed.notify_all();
}

} // namespace vots::server
