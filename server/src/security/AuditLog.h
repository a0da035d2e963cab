// AuditLog: `vots serve --audit-log FILE`, one JSON line per access to patient data (docs/API.md,
// "Audit trail"): appended, flushed at once, rotated by size; a failed write makes the data routes answer
// 503 until the file can be written again, never serve unaudited.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

namespace vots::server {

struct AccessToken;

/// The audit action of a request ("list-datasets", "render", "turntable", "fit", "pacs-query",
/// "pacs-retrieve", "pacs-store"), nullopt for one that touches no patient data.
std::optional<std::string> auditAction(const std::string& method, const std::string& path);

/// A line's time: UTC with milliseconds, "2026-12-05T08:00:00.123Z".
std::string auditTime(std::chrono::system_clock::time_point at);

/// A line's user: the token's name, null without a token (never the token itself).
nlohmann::json auditUser(const AccessToken* token);

/// The fields of every line: time (UTC, milliseconds), client (after a trusted proxy), the token's name
/// or null (never the token), action, dataset (or null) and status.
nlohmann::json auditFields(std::chrono::system_clock::time_point at, const std::string& client,
                           const nlohmann::json& user, const std::string& action,
                           const nlohmann::json& dataset, int status);

/// The line for an audited request: time (UTC), client (after a trusted proxy), the token's name (never
/// the token), action, dataset, DICOM study and series UIDs where the request names them, and status.
nlohmann::json auditLine(const std::string& action, const httplib::Request& req, const httplib::Response& res,
                         const AccessToken* token);

class AuditLog {
public:
    /// Opens (appending) the file; throws fit::InputError when it cannot. Beyond rotateBytes the file
    /// becomes FILE.1 (replacing an older one) and a new FILE is begun.
    AuditLog(std::filesystem::path file, std::uint64_t rotateBytes);
    ~AuditLog();
    AuditLog(const AuditLog&) = delete;
    AuditLog& operator=(const AuditLog&) = delete;

    /// Whether lines can be written: after a failure it opens the file again and writes an
    /// "audit-log-resumed" line, true once that succeeds.
    bool ready();
    /// Appends and flushes one line; a failure is reported on stderr and makes ready() false.
    void write(const nlohmann::json& line);

private:
    bool openLocked();
    void failLocked(const std::string& why);

    const std::filesystem::path mFile;
    const std::uint64_t mRotateBytes;
    std::mutex mMutex;
    std::FILE* mOut = nullptr; // null after a failure
};

} // namespace vots::server
