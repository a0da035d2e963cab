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
    std::lock_guard lock(mMutex);
    int& count = mCounts[client];
    if (count >= mPerClient)
        throw HttpError(429, "too many " + mWhat + " in progress from " + client + " (at most " +
                                 std::to_string(mPerClient) +
                                 " per client); try again when one has finished");
    ++count;
    return Ticket(this, client);
}

int ClientQuota::inProgress(const std::string& client) const {
    std::lock_guard lock(mMutex);
    const auto it = mCounts.find(client);
    return it == mCounts.end() ? 0 : it->second;
}

void ClientQuota::leave(const std::string& client) {
    std::lock_guard lock(mMutex);
    const auto it = mCounts.find(client);
    if (it != mCounts.end() && --it->second <= 0) mCounts.erase(it);
}

} // namespace vots::server
