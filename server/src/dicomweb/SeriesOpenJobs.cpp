// SeriesOpenJobs: announce the series, reuse its kept copy or retrieve it with progress, then load it.
#include "dicomweb/SeriesOpenJobs.h"

#include "HttpError.h"
#include "dicomweb/JobThreads.h"

#include "vots/fit/DicomIntake.h"
#include "vots/fit/MemoryBudget.h"

#include <algorithm>

namespace vots::server {

std::string pacsDatasetName(const std::string& service, const std::string& seriesUid) {
    std::string name = service + "-" + seriesUid;
    for (char& c : name)
        if (c == '.') c = '_';
    return name;
}

SeriesOpenJobs::SeriesOpenJobs(const std::vector<DicomWebService>& services,
                               const std::filesystem::path& cacheRoot, std::uint64_t cacheBytes,
                               DatasetRegistry& registry, MemoryAdmission& memory)
    : mServices(services), mRegistry(registry), mMemory(memory) {
    if (services.empty()) return;
    mCache = std::make_unique<RetrievedSeriesCache>(cacheRoot, cacheBytes);
    // A restarted server lists what it keeps, as it was retrieved, so that links to it work at once; an
    // open from the panel checks it against the PACS again. The most recently opened copy wins.
    for (const KeptSeries& kept : mCache->kept()) {
        const bool configured = std::any_of(services.begin(), services.end(),
                                            [&](const DicomWebService& s) { return s.name == kept.service; });
        if (configured)
            mRegistry.offerDicomFolder(pacsDatasetName(kept.service, kept.seriesUid), kept.folder);
    }
}

SeriesOpenJobs::~SeriesOpenJobs() {
    stopAndJoinJobs(mMutex, mJobs, &Job::cancel);
}

const DicomWebService& SeriesOpenJobs::service(const std::string& name) const {
    for (const DicomWebService& s : mServices)
        if (s.name == name) return s;
    throw HttpError(404, "unknown PACS '" + name + "'");
}

SeriesOpenSnapshot SeriesOpenJobs::open(const std::string& serviceName, const std::string& studyUid,
                                        const std::string& seriesUid) {
    service(serviceName); // 404 before anything starts
    std::lock_guard lock(mMutex);
    for (const auto& [id, job] : mJobs) {
        const SeriesOpenSnapshot& s = job->visible;
        if (!s.ended() && s.service == serviceName && s.seriesUid == seriesUid) return s;
    }
    if (mRunning >= MAX_RUNNING)
        throw HttpError(429,
                        std::to_string(MAX_RUNNING) + " series are being opened; try again when one is in");
    auto job = std::make_unique<Job>();
    job->visible.id = mNextId++;
    job->visible.service = serviceName;
    job->visible.studyUid = studyUid;
    job->visible.seriesUid = seriesUid;
    Job& started = *job;
    mJobs.emplace(started.visible.id, std::move(job));
    ++mRunning;
    started.thread = std::thread([this, &started] { run(started); });
    return started.visible;
}

void SeriesOpenJobs::update(Job& job, const std::function<void(SeriesOpenSnapshot&)>& change) {
    std::lock_guard lock(mMutex);
    change(job.visible);
}

namespace {

/// Between the steps that cannot be stopped midway (the announcement, the load): a cancel ends the open.
void stopIfCancelled(const std::atomic<bool>& cancel, const pacs::DicomWebSeries& series) {
    if (cancel) throw HttpError(409, series.describe() + ": the open was cancelled");
}

} // namespace

void SeriesOpenJobs::run(Job& job) {
    const DicomWebService& service = this->service(job.visible.service);
    const pacs::DicomWebSeries series{service.endpoint, job.visible.studyUid, job.visible.seriesUid};
    const std::string name = pacsDatasetName(service.name, series.seriesUid);
    std::exception_ptr failure;
    try {
        update(job, [](SeriesOpenSnapshot& s) { s.state = SeriesOpenState::Announcing; });
        // QIDO and the series' metadata only: enough to know whether the kept copy is still the series.
        const pacs::SeriesAnnouncement announced = pacs::announceSeries(series, service.access);
        update(job, [&](SeriesOpenSnapshot& s) { s.total = announced.instanceCount; });
        stopIfCancelled(job.cancel, series);
        std::optional<std::filesystem::path> folder =
            mCache->find(series.seriesUid, announced.sopInstanceUids);
        bool readAlready = false;
        if (folder) {
            update(job, [&](SeriesOpenSnapshot& s) {
                s.fromCache = true;
                s.received = s.total;
            });
        } else {
            update(job, [](SeriesOpenSnapshot& s) { s.state = SeriesOpenState::Retrieving; });
            // Each instance is decoded as it arrives, so the volume is in shortly after the last one.
            std::optional<MemoryReservation> reserved;
            std::optional<fit::DicomSeriesIntake> intake;
            fit::DicomIntakeResult read;
            pacs::SeriesRetrieveOptions options;
            options.spoolParent = mCache->spoolParent().string();
            options.announced = announced;
            options.cancel = &job.cancel;
            options.admit = [&](const fit::VolumeHeaderInfo& grid) {
                reserved = mMemory.admit(fit::estimateLoadAndFitBytes(grid, DATASET_STORAGE),
                                         "series " + series.seriesUid + " (" + grid.describe() + ")");
                intake.emplace(grid, DATASET_STORAGE);
            };
            options.received = [&](const std::string& path) { intake->add(path); };
            options.countImages = [&] {
                read = intake->finish(name);
                return read.images;
            };
            options.progress = [&](int received, int total) {
                update(job, [&](SeriesOpenSnapshot& s) {
                    s.received = received;
                    s.total = total;
                });
            };
            const pacs::RetrievedSeries retrieved = pacs::retrieveSeries(series, service.access, options);
            folder = mCache->keep({service.name, series.studyUid, series.seriesUid, {}},
                                  announced.sopInstanceUids, retrieved);
            if (read.volume) {
                read.volume->name = folder->filename().string(); // as the folder's reader names it
                mRegistry.offerLoadedDicomFolder(name, *folder, std::move(*read.volume),
                                                 {read.valueRange, read.contentCrc});
                readAlready = true;
            }
        }
        stopIfCancelled(job.cancel, series);
        update(job, [](SeriesOpenSnapshot& s) { s.state = SeriesOpenState::Loading; });
        if (!readAlready) mRegistry.offerDicomFolder(name, *folder);
        mRegistry.find(name); // loaded now, admitted against the memory budget as any dataset
        update(job, [&](SeriesOpenSnapshot& s) {
            s.dataset = name;
            s.state = SeriesOpenState::Done;
        });
    } catch (...) {
        failure = std::current_exception();
    }
    endJob(mMutex, mJobs, mFinished, mRunning, job, failure, job.cancel.load(), KEEP_FINISHED);
}

SeriesOpenSnapshot SeriesOpenJobs::snapshot(std::uint64_t id) const {
    std::lock_guard lock(mMutex);
    return findJobLocked(mJobs, id, "series open").visible;
}

SeriesOpenSnapshot SeriesOpenJobs::cancel(std::uint64_t id) {
    std::lock_guard lock(mMutex);
    Job& job = findJobLocked(mJobs, id, "series open");
    job.cancel = true;
    return job.visible;
}

} // namespace vots::server
