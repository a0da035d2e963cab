// Opening a PACS series as a dataset: a job per series that announces, retrieves (or finds it kept), loads.
#pragma once

#include "datasets/DatasetRegistry.h"
#include "datasets/MemoryAdmission.h"
#include "dicomweb/RetrievedSeriesCache.h"
#include "vots/fit/EnumNames.h"
#include "vots/server/Server.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vots::server {

/// The steps of an open, in order, and how it ended.
enum class SeriesOpenState { Queued, Announcing, Retrieving, Loading, Done, Failed, Cancelled };
inline constexpr auto SERIES_OPEN_STATE_NAMES =
    fit::nameTable<SeriesOpenState>("series open state", {{SeriesOpenState::Queued, "queued"},
                                                          {SeriesOpenState::Announcing, "announcing"},
                                                          {SeriesOpenState::Retrieving, "retrieving"},
                                                          {SeriesOpenState::Loading, "loading"},
                                                          {SeriesOpenState::Done, "done"},
                                                          {SeriesOpenState::Failed, "failed"},
                                                          {SeriesOpenState::Cancelled, "cancelled"}});
constexpr const auto& namesOf(SeriesOpenState) {
    return SERIES_OPEN_STATE_NAMES;
}

/// What GET /api/pacs/opens/{id} reports.
struct SeriesOpenSnapshot {
    std::uint64_t id = 0;
    std::string service;
    std::string studyUid;
    std::string seriesUid;
    SeriesOpenState state = SeriesOpenState::Queued;
    int received = 0;       // instances received so far
    int total = 0;          // the series' instances (0 until announced)
    bool fromCache = false; // kept on disk from an earlier open: no retrieve
    std::string dataset;    // the dataset's name once done
    int errorStatus = 0;    // failed: the HTTP status the failure maps to (401, 404, 502, 504, 507)
    std::string error;

    bool ended() const { return state >= SeriesOpenState::Done; }
};

/// Thread-safe. Each open runs on a thread of its own, at most MAX_RUNNING at once (429 beyond); an open
/// of a series already being opened joins that job. The dataset is named "<service>-<SeriesInstanceUID
/// with '_' for '.'>" and offered to the registry like a DICOM folder of the data folders; so are, on
/// construction, the series the cache keeps from the services configured.
class SeriesOpenJobs {
public:
    static constexpr int MAX_RUNNING = 2;
    static constexpr std::size_t KEEP_FINISHED = 32;

    /// The retrieved series are kept in `cacheRoot` (RetrievedSeriesCache), made only when there are
    /// services: a server without a PACS writes nothing for them.
    SeriesOpenJobs(const std::vector<DicomWebService>& services, const std::filesystem::path& cacheRoot,
                   std::uint64_t cacheBytes, DatasetRegistry& registry, MemoryAdmission& memory);
    ~SeriesOpenJobs(); // cancels every open and joins the threads

    /// The service of that name; HttpError 404 for an unknown one.
    const DicomWebService& service(const std::string& name) const;
    /// Starts (or joins) the open of a series; HttpError 404 for an unknown service, 429 when too many run.
    SeriesOpenSnapshot open(const std::string& service, const std::string& studyUid,
                            const std::string& seriesUid);
    /// HttpError 404 for an unknown or forgotten id.
    SeriesOpenSnapshot snapshot(std::uint64_t id) const;
    /// Asks a running open to stop (it ends as cancelled); HttpError 404 for an unknown id.
    SeriesOpenSnapshot cancel(std::uint64_t id);

private:
    struct Job {
        SeriesOpenSnapshot visible; // what the API answers, written under mMutex
        std::atomic<bool> cancel{false};
        std::thread thread;
    };
    void run(Job& job);
    void update(Job& job, const std::function<void(SeriesOpenSnapshot&)>& change);

    const std::vector<DicomWebService>& mServices;
    std::unique_ptr<RetrievedSeriesCache> mCache; // null without services
    DatasetRegistry& mRegistry;
    MemoryAdmission& mMemory;

    mutable std::mutex mMutex;
    std::uint64_t mNextId = 1;
    int mRunning = 0;
    std::map<std::uint64_t, std::unique_ptr<Job>> mJobs;
    std::deque<std::uint64_t> mFinished; // oldest first; forgotten beyond KEEP_FINISHED
};

/// "<service>-<SeriesInstanceUID with '_' for '.'>".
std::string pacsDatasetName(const std::string& service, const std::string& seriesUid);

} // namespace vots::server
