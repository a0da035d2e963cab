// StreamAudit: a viewer socket's stills and refusals line by line, its drafts one line per burst.
#include "security/StreamAudit.h"

#include "security/AuditLog.h"

namespace vots::server {

StreamAudit::StreamAudit(AuditLog* log, std::string client, nlohmann::json user)
    : mLog(log), mClient(std::move(client)), mUser(std::move(user)) {}

StreamAudit::~StreamAudit() {
    closed();
}

bool StreamAudit::ready() const {
    return !mLog || mLog->ready();
}

void StreamAudit::frame(const std::string& dataset, bool still, int status) {
    if (!mLog) return;
    const Clock::time_point now = Clock::now();
    std::lock_guard lock(mMutex);
    const bool draft = !still && status == 200;
    if (mBurstFrames > 0 && (!draft || dataset != mBurstDataset || now - mBurstStart >= MAX_BURST))
        writeBurstLocked();
    if (!draft)
        return mLog->write(
            auditFields(now, mClient, mUser, still ? "stream-still" : "stream-draft", dataset, status));
    if (mBurstFrames == 0) {
        mBurstDataset = dataset;
        mBurstStart = now;
    }
    ++mBurstFrames;
    mBurstEnd = now;
}

void StreamAudit::closed() {
    if (!mLog) return;
    std::lock_guard lock(mMutex);
    if (mBurstFrames > 0) writeBurstLocked();
}

void StreamAudit::writeBurstLocked() {
    nlohmann::json line = auditFields(mBurstStart, mClient, mUser, "stream-drafts", mBurstDataset, 200);
    line["frames"] = mBurstFrames;
    line["until"] = auditTime(mBurstEnd);
    mLog->write(line);
    mBurstFrames = 0;
}

} // namespace vots::server
