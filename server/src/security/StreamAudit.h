// StreamAudit: the audit trail of one viewer socket (docs/API.md, "Audit trail"): a line per still, and
// one per burst of drafts (a drag) with its frame count, since a line per draft would be 24 a second.
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace vots::server {

class AuditLog;

class StreamAudit {
public:
    // A drag longer than this is written as several bursts, so no access waits long for its line.
    static constexpr std::chrono::seconds MAX_BURST{10};

    /// `log` null: nothing is audited. `client` as the guard sees it (after a trusted proxy), `user` the
    /// token's name or null.
    StreamAudit(AuditLog* log, std::string client, nlohmann::json user);
    ~StreamAudit(); // writes the burst still open
    StreamAudit(const StreamAudit&) = delete;
    StreamAudit& operator=(const StreamAudit&) = delete;

    /// Whether frames may be drawn: false while the audit log cannot be written (never serve unaudited).
    bool ready() const;
    /// A frame of `dataset` drawn (status 200) or refused: a still or a refusal gets its own line at once
    /// ("stream-still" / "stream-draft"); drawn drafts are counted into one "stream-drafts" line, written at
    /// the next still, a change of dataset, after MAX_BURST, or when the socket closes.
    void frame(const std::string& dataset, bool still, int status);
    /// The socket closed: the open burst's line.
    void closed();

private:
    using Clock = std::chrono::system_clock;
    void writeBurstLocked();

    AuditLog* const mLog;
    const std::string mClient;
    const nlohmann::json mUser;
    std::mutex mMutex;
    std::string mBurstDataset;
    std::uint64_t mBurstFrames = 0;
    Clock::time_point mBurstStart, mBurstEnd;
};

} // namespace vots::server
