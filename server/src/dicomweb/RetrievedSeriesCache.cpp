// RetrievedSeriesCache: retrieved spool folders moved into the server's cache folder, found again by the
// series' instance list, and trimmed least recently opened first.
#include "dicomweb/RetrievedSeriesCache.h"

#include "LeastRecentlyUsed.h"

#include "vots/fit/Error.h"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr const char* RECORD_EXTENSION = ".json";
constexpr const char* SPOOL_PREFIX = "spool-";

/// Removes ROOT/spool-<pid>/ of processes that no longer run: retrieves they left half done.
void removeStaleSpools(const fs::path& root) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(root, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(SPOOL_PREFIX, 0) != 0) continue;
        const std::string digits = name.substr(std::string(SPOOL_PREFIX).size());
        if (digits.empty() || digits.size() > 9 ||
            digits.find_first_not_of("0123456789") != std::string::npos)
            continue;
        const pid_t pid = static_cast<pid_t>(std::stol(digits));
        if (kill(pid, 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
    }
}

std::uint32_t crcOf(std::uint32_t crc, const std::string& text) {
    return static_cast<std::uint32_t>(
        crc32(crc, reinterpret_cast<const Bytef*>(text.data()), static_cast<uInt>(text.size())));
}

struct FolderContent {
    std::uint64_t bytes = 0;
    int files = 0;
};

/// How many files a folder holds and their bytes, from their sizes alone: reading a 500 MB series again
/// here would hold back its first image.
FolderContent folderContent(const fs::path& folder) {
    FolderContent content;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.is_regular_file()) {
            content.bytes += entry.file_size();
            ++content.files;
        }
    return content;
}

std::uint64_t folderBytes(const fs::path& folder) {
    std::uint64_t total = 0;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const auto size = entry.file_size(ec);
        if (!ec) total += size;
    }
    return total;
}

} // namespace

std::string retrievedSeriesKey(const std::string& seriesUid, std::vector<std::string> sopInstanceUids) {
    std::sort(sopInstanceUids.begin(), sopInstanceUids.end());
    std::uint32_t crc = 0;
    for (const std::string& uid : sopInstanceUids)
        crc = crcOf(crc, uid + '\n');
    char hex[9];
    std::snprintf(hex, sizeof hex, "%08x", crc);
    return seriesUid + "-" + hex;
}

RetrievedSeriesCache::RetrievedSeriesCache(fs::path root, std::uint64_t budgetBytes)
    : mRoot(std::move(root)), mBudget(budgetBytes) {
    std::error_code ec;
    if (!mRoot.empty() && !fs::create_directories(mRoot, ec) && ec) {
        std::cerr << "vots serve: warning: folder '" << mRoot.string()
                  << "' for retrieved PACS series is not used (" << ec.message()
                  << "); they are kept in a temporary folder until the server stops\n";
        mRoot.clear();
    }
    if (mRoot.empty()) {
        std::string pattern = (fs::temp_directory_path() / "vots-retrieved-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw fit::InputError("cannot make a temporary folder for retrieved PACS series: " +
                                  std::string(std::strerror(errno)));
        mRoot = pattern;
        mOwnsRoot = true;
    }
    removeStaleSpools(mRoot);
    mSpool = mRoot / (SPOOL_PREFIX + std::to_string(getpid()));
    fs::create_directories(mSpool);
}

RetrievedSeriesCache::~RetrievedSeriesCache() {
    std::error_code ignored;
    fs::remove_all(mSpool, ignored); // empty unless a retrieve failed to clean up after itself
    if (mOwnsRoot) fs::remove_all(mRoot, ignored);
}

std::optional<fs::path> RetrievedSeriesCache::find(const std::string& seriesUid,
                                                   const std::vector<std::string>& sopInstanceUids) {
    const std::string key = retrievedSeriesKey(seriesUid, sopInstanceUids);
    std::lock_guard lock(mMutex);
    const fs::path record = mRoot / (key + RECORD_EXTENSION);
    std::error_code ec;
    if (!fs::is_regular_file(record, ec) || !fs::is_directory(mRoot / key, ec)) return std::nullopt;
    fs::last_write_time(record, fs::file_time_type::clock::now(), ec); // recently opened: trimmed last
    return mRoot / key;
}

fs::path RetrievedSeriesCache::keep(const KeptSeries& origin, const std::vector<std::string>& sopInstanceUids,
                                    const pacs::RetrievedSeries& retrieved) {
    const std::string key = retrievedSeriesKey(origin.seriesUid, sopInstanceUids);
    const FolderContent content = folderContent(retrieved.folder());
    std::lock_guard lock(mMutex);
    const fs::path folder = mRoot / key;
    const fs::path record = mRoot / (key + RECORD_EXTENSION);
    std::error_code ec;
    fs::remove(record, ec);
    fs::remove_all(folder, ec);                 // an incomplete earlier copy
    fs::rename(retrieved.folder(), folder, ec); // the spool folder's owner then finds nothing to remove
    if (ec)
        throw fit::InputError("cannot keep the retrieved series in " + mRoot.string() + ": " + ec.message());
    const nlohmann::json received = {{"service", origin.service},
                                     {"studyInstanceUid", origin.studyUid},
                                     {"seriesInstanceUid", origin.seriesUid},
                                     {"instances", content.files},
                                     {"bytes", content.bytes},
                                     {"perInstance", retrieved.perInstance}};
    const fs::path temporary = record.string() + ".tmp";
    {
        std::ofstream out(temporary);
        out << received.dump(2) << "\n";
        if (!out) throw fit::InputError("cannot write " + temporary.string());
    }
    fs::rename(temporary, record, ec); // the record last: a folder without one is incomplete
    if (ec) throw fit::InputError("cannot write " + record.string() + ": " + ec.message());
    trimToBudget(folder);
    return folder;
}

std::vector<KeptSeries> RetrievedSeriesCache::kept() const {
    std::lock_guard lock(mMutex);
    std::vector<std::pair<fs::file_time_type, KeptSeries>> found;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(mRoot, ec)) {
        if (entry.path().extension() != RECORD_EXTENSION) continue;
        fs::path folder = entry.path();
        folder.replace_extension();
        std::ifstream in(entry.path());
        const nlohmann::json record = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
        if (!record.is_object() || !fs::is_directory(folder, ec)) continue;
        KeptSeries series{record.value("service", ""), record.value("studyInstanceUid", ""),
                          record.value("seriesInstanceUid", ""), folder};
        if (series.service.empty() || series.seriesUid.empty()) continue;
        found.emplace_back(entry.last_write_time(ec), std::move(series));
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<KeptSeries> out;
    for (auto& [opened, series] : found)
        out.push_back(std::move(series));
    return out;
}

void RetrievedSeriesCache::trimToBudget(const fs::path& keep) const {
    std::vector<CachedOnDisk> kept;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(mRoot, ec)) {
        if (entry.path().extension() != RECORD_EXTENSION) continue;
        fs::path folder = entry.path();
        folder.replace_extension();
        kept.push_back({folder, entry.last_write_time(ec), folderBytes(folder)});
    }
    trimLeastRecentlyUsed(std::move(kept), mBudget, keep, [](const CachedOnDisk& k) {
        std::error_code ignored;
        fs::remove(k.path.string() + RECORD_EXTENSION, ignored); // the record first: never a half-removed hit
        fs::remove_all(k.path, ignored);
        return true;
    });
}

} // namespace vots::server
