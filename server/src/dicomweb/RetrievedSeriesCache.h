// The retrieved PACS series kept on disk: one folder of instances per series and instance list, LRU-bounded.
#pragma once

#include "vots/pacs/SeriesRetrieve.h"

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace vots::server {

/// Thread-safe. A series is kept as ROOT/KEY/ (the instance files, read as a DICOM folder) beside
/// ROOT/KEY.json (what was received), where KEY is the SeriesInstanceUID and a CRC-32 of its sorted
/// SOPInstanceUIDs: a series the PACS has changed since (an instance more, less or replaced) has another
/// key, so it is fetched again. A folder without its .json was never completed and is not used.
/// Beyond the byte budget the least recently opened series are removed (never the one just kept).
class RetrievedSeriesCache {
public:
    /// root empty: a private temporary folder, removed with this object.
    RetrievedSeriesCache(std::filesystem::path root, std::uint64_t budgetBytes);
    ~RetrievedSeriesCache();
    RetrievedSeriesCache(const RetrievedSeriesCache&) = delete;
    RetrievedSeriesCache& operator=(const RetrievedSeriesCache&) = delete;

    /// Where retrieves spool (pacs::SeriesRetrieveOptions::spoolParent): on the same file system, so a
    /// finished spool folder is moved into place, not copied.
    const std::filesystem::path& root() const { return mRoot; }

    /// The folder of this series as announced, when it was kept complete; marks it recently opened.
    std::optional<std::filesystem::path> find(const std::string& seriesUid,
                                              const std::vector<std::string>& sopInstanceUids);
    /// Moves the retrieved spool folder into place, records what was received (instance count, bytes and
    /// a CRC-32 of the files), trims the cache to its budget, and returns the kept folder. Throws
    /// fit::InputError when it cannot be moved (then the spool folder goes with `retrieved`).
    std::filesystem::path keep(const std::string& seriesUid, const std::vector<std::string>& sopInstanceUids,
                               const pacs::RetrievedSeries& retrieved);

private:
    void trimToBudget(const std::filesystem::path& keep) const;

    std::filesystem::path mRoot;
    bool mOwnsRoot = false;
    const std::uint64_t mBudget;
    mutable std::mutex mMutex;
};

/// The cache key of a series with these instances: "<SeriesInstanceUID>-<CRC-32 hex>".
std::string retrievedSeriesKey(const std::string& seriesUid, std::vector<std::string> sopInstanceUids);

} // namespace vots::server
