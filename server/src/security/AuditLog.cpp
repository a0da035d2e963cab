// AuditLog: the audited requests, their JSON lines, and the append-only file they go to.
#include "security/AuditLog.h"

#include "routes/Params.h"
#include "vots/fit/Error.h"
#include "vots/server/Exposure.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <iostream>
#include <regex>

namespace vots::server {
namespace {

const std::regex PACS_SEARCH(R"(/api/pacs/[^/]+/studies(/([0-9.]+)/series)?)");
const std::regex PACS_OPEN(R"(/api/pacs/[^/]+/studies/([0-9.]+)/series/([0-9.]+)/open)");

/// The dataset a request names: its dataset= parameter, else the "dataset" of a JSON body (a fit), else
/// that of its "params" (a PACS store).
nlohmann::json datasetOf(const httplib::Request& req) {
    const QueryParams query = targetQueryParams(req.target);
    if (const auto it = query.find("dataset"); it != query.end()) return it->second;
    const auto body = nlohmann::json::parse(req.body, nullptr, false);
    if (body.is_object() && body.contains("dataset") && body["dataset"].is_string()) return body["dataset"];
    if (body.is_object() && body.contains("params") && body["params"].is_object() &&
        body["params"].contains("dataset") && body["params"]["dataset"].is_string())
        return body["params"]["dataset"];
    return nullptr;
}

} // namespace

std::string auditTime(std::chrono::system_clock::time_point at) {
    const std::time_t seconds = std::chrono::system_clock::to_time_t(at);
    const auto millis =
        std::chrono::duration_cast<std::chrono::milliseconds>(at.time_since_epoch()).count() % 1000;
    std::tm utc{};
    gmtime_r(&seconds, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
    const std::string ms = std::to_string(1000 + millis).substr(1); // three digits
    return std::string(text) + "." + ms + "Z";
}

std::optional<std::string> auditAction(const std::string& method, const std::string& path) {
    if (method == "GET" && path == "/api/datasets") return "list-datasets";
    if (method == "GET" && path == "/render") return "render";
    if (method == "GET" && path == "/turntable") return "turntable";
    if (method == "POST" && path == "/api/fit") return "fit";
    if (method == "GET" && std::regex_match(path, PACS_SEARCH)) return "pacs-query";
    if (method == "POST" && std::regex_match(path, PACS_OPEN)) return "pacs-retrieve";
    if (method == "POST" && path.rfind("/api/pacs/", 0) == 0 && path.size() > 6 &&
        path.compare(path.size() - 6, 6, "/store") == 0)
        return "pacs-store";
    return std::nullopt;
}

nlohmann::json auditUser(const AccessToken* token) {
    return token ? nlohmann::json(token->name) : nlohmann::json(nullptr);
}

nlohmann::json auditFields(std::chrono::system_clock::time_point at, const std::string& client,
                           const nlohmann::json& user, const std::string& action,
                           const nlohmann::json& dataset, int status) {
    return {{"time", auditTime(at)}, {"client", client},   {"user", user},
            {"action", action},      {"dataset", dataset}, {"status", status}};
}

nlohmann::json auditLine(const std::string& action, const httplib::Request& req, const httplib::Response& res,
                         const AccessToken* token) {
    nlohmann::json line = auditFields(std::chrono::system_clock::now(), req.remote_addr, auditUser(token),
                                      action, datasetOf(req), res.status);
    std::smatch m;
    if (std::regex_match(req.path, m, PACS_OPEN)) {
        line["study"] = m[1].str();
        line["series"] = m[2].str();
    } else if (std::regex_match(req.path, m, PACS_SEARCH) && m[2].matched) {
        line["study"] = m[2].str();
    }
    return line;
}

AuditLog::AuditLog(std::filesystem::path file, std::uint64_t rotateBytes)
    : mFile(std::move(file)), mRotateBytes(rotateBytes) {
    std::lock_guard lock(mMutex);
    if (!openLocked())
        throw fit::InputError("cannot open the audit log '" + mFile.string() + "': " + std::strerror(errno));
}

AuditLog::~AuditLog() {
    if (mOut) std::fclose(mOut);
}

bool AuditLog::openLocked() {
    mOut = std::fopen(mFile.c_str(), "a");
    return mOut != nullptr;
}

void AuditLog::failLocked(const std::string& why) {
    std::cerr << "vots serve: cannot write the audit log '" << mFile.string() << "' (" << why
              << "): data requests are answered 503 until it can be written" << std::endl;
    if (mOut) std::fclose(mOut);
    mOut = nullptr;
}

bool AuditLog::ready() {
    std::lock_guard lock(mMutex);
    if (mOut) return true;
    // After a failure only a line written proves the file works again; it also marks the gap.
    const std::string resumed =
        nlohmann::json{{"time", auditTime(std::chrono::system_clock::now())}, {"action", "audit-log-resumed"}}
            .dump() +
        "\n";
    if (!openLocked()) return false;
    if (std::fwrite(resumed.data(), 1, resumed.size(), mOut) == resumed.size() && std::fflush(mOut) == 0)
        return true;
    std::fclose(mOut);
    mOut = nullptr;
    return false;
}

void AuditLog::write(const nlohmann::json& line) {
    std::lock_guard lock(mMutex);
    if (!mOut) return; // failed before (reported then): ready() is false until the file works again
    const std::string text = line.dump() + "\n";
    // Flushed with every line: what was served is on disk (or in the kernel's hands) within the second.
    if (std::fwrite(text.data(), 1, text.size(), mOut) != text.size() || std::fflush(mOut) != 0)
        return failLocked(std::strerror(errno));
    const long size = std::ftell(mOut);
    if (size < 0 || static_cast<std::uint64_t>(size) < mRotateBytes) return;
    std::fclose(mOut);
    mOut = nullptr;
    std::error_code ec;
    std::filesystem::rename(mFile, mFile.string() + ".1", ec);
    if (ec) return failLocked("rotating it: " + ec.message());
    if (!openLocked()) failLocked(std::strerror(errno));
}

} // namespace vots::server
