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

/// Where a kept series came from, as its record says.
struct KeptSeries {
    std::string service; // the --dicomweb NAME it was opened from
    std::string studyUid;
    std::string seriesUid;
    std::filesystem::path folder;
};

/// Thread-safe. A series is kept as ROOT/KEY/ (the instance files, read as a DICOM folder) beside
/// ROOT/KEY.json (what was received), where KEY is the SeriesInstanceUID and a CRC-32 of its sorted
/// SOPInstanceUIDs: a series the PACS has changed since (an instance more, less or replaced) has another
/// key, so it is fetched again. A folder without its .json was never completed and is not used.
/// Beyond the byte budget the least recently opened series are removed (never the one just kept).
/// Retrieves spool into ROOT/spool-<pid>/; those of processes that no longer run are removed on
/// construction (another server may share the folder).
class RetrievedSeriesCache {
public:
    /// root empty, or a folder that cannot be made (logged): a private temporary folder, removed with this
    /// object.
    RetrievedSeriesCache(std::filesystem::path root, std::uint64_t budgetBytes);
    ~RetrievedSeriesCache();
    RetrievedSeriesCache(const RetrievedSeriesCache&) = delete;
    RetrievedSeriesCache& operator=(const RetrievedSeriesCache&) = delete;

    const std::filesystem::path& root() const { return mRoot; }
    /// Where this process's retrieves spool (pacs::SeriesRetrieveOptions::spoolParent): under the root,
    /// on the same file system, so a finished spool folder is moved into place, not copied.
    const std::filesystem::path& spoolParent() const { return mSpool; }

    /// The folder of this series as announced, when it was kept complete; marks it recently opened.
    std::optional<std::filesystem::path> find(const std::string& seriesUid,
                                              const std::vector<std::string>& sopInstanceUids);
    /// Moves the retrieved spool folder into place, records what was received (instance count, bytes and
    /// a CRC-32 of the files), trims the cache to its budget, and returns the kept folder. Throws
    /// fit::InputError when it cannot be moved (then the spool folder goes with `retrieved`).
    std::filesystem::path keep(const KeptSeries& origin, const std::vector<std::string>& sopInstanceUids,
                               const pacs::RetrievedSeries& retrieved);
    /// Every complete kept series, the least recently opened first.
    std::vector<KeptSeries> kept() const;

private:
    void trimToBudget(const std::filesystem::path& keep) const;

    std::filesystem::path mRoot;
    std::filesystem::path mSpool;
    bool mOwnsRoot = false;
    const std::uint64_t mBudget;
    mutable std::mutex mMutex;
};

/// The cache key of a series with these instances: "<SeriesInstanceUID>-<CRC-32 hex>".
std::string retrievedSeriesKey(const std::string& seriesUid, std::vector<std::string> sopInstanceUids);

} // namespace vots::server
