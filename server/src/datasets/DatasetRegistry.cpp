// DatasetRegistry: finds volume files by stem, DICOM series folders and .vots files, loads each once on
// demand, derives window presets.
#include "datasets/DatasetRegistry.h"

#include "datasets/DatasetRegistryVots.h"

#include "HttpError.h"
#include "routes/HttpJson.h"
#include "routes/Params.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeLoad.h"
#include "vots/fit/VolumePlanes.h"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <set>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr float CT_MIN_HU = -900.f; // air is about -1000 HU; a minimum this low means CT
// Frames beside frame 0 get a quarter of the budget by default: the rest is for frame 0s, fits and the
// renderer, and a viewer cycling a cine reloads a frame in about the time it draws one.
constexpr std::uint64_t HELD_FRAMES_SHARE = 4;

/// The dataset name of a file ("cranium" for cranium.nhdr or cranium.nii.gz), empty if not a volume.
std::string volumeStem(const fs::path& file) {
    const std::string name = file.filename().string();
    for (const char* ext : {".nii.gz", ".nrrd", ".nhdr", ".nii", ".mgh", ".mgz", ".mhd", ".mha"}) {
        const std::string e = ext;
        if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0)
            return name.substr(0, name.size() - e.size());
    }
    return {};
}

/// What follows from a volume dataset's value range.
void describeRange(Dataset& dataset, std::array<float, 2> range) {
    dataset.range = range;
    dataset.background = fit::defaultBackground(range);
    dataset.defaultEps = static_cast<float>(fit::EpsSpec{}.resolve(range[0], range[1]));
    dataset.isCt = range[0] <= CT_MIN_HU;
    dataset.presets = windowPresets(range, dataset.isCt);
}

/// The dataset of a volume loaded from `path`; `known`: its value range and content CRC when its reader
/// gave them already (they are read from the samples otherwise).
std::shared_ptr<Dataset> datasetOfVolume(const std::string& name, const fs::path& path,
                                         const std::string& dicomSeries, const fit::VolumeHeaderInfo& header,
                                         std::shared_ptr<const fit::Volume> volume,
                                         const std::optional<VolumeSummary>& known = std::nullopt) {
    auto dataset = std::make_shared<Dataset>();
    dataset->loadAndFitBytes = fit::estimateLoadAndFitBytes(header, DATASET_STORAGE);
    const std::uint64_t held = fit::estimateLoadedVolumeBytes(header, DATASET_STORAGE);
    dataset->fitBytes = dataset->loadAndFitBytes > held ? dataset->loadAndFitBytes - held : 0;
    dataset->name = name;
    dataset->path = path;
    dataset->dicomSeries = dicomSeries;
    describeRange(*dataset, known ? known->valueRange : volume->valueRange());
    dataset->contentCrc = known ? known->contentCrc : volume->contentCrc();
    dataset->volume = std::move(volume);
    return dataset;
}

std::shared_ptr<Dataset> loadDataset(const std::string& name, const fs::path& path,
                                     const std::string& dicomSeries, const fit::VolumeHeaderInfo& header,
                                     int frame) {
    auto dataset = datasetOfVolume(name, path, dicomSeries, header,
                                   std::make_shared<fit::Volume>(fit::loadVolume(
                                       path.string(), std::nullopt, DATASET_STORAGE, dicomSeries, frame)));
    dataset->frame = frame;
    return dataset;
}

/// Under mpirun: the ranks read the samples of `frame`, each its z cells' planes; this process reads the
/// grid from the first plane and holds no samples.
std::shared_ptr<Dataset> summarizeDataset(const std::string& name, const fs::path& path,
                                          const std::string& dicomSeries, dist::FrameRanks& ranks,
                                          int frame) {
    if (!dicomSeries.empty())
        throw fit::InputError(
            "under mpirun a folder of several DICOM series is not drawn across the ranks yet");
    const dist::VolumeSummary summary = ranks.summarize(path, frame);
    auto dataset = std::make_shared<Dataset>();
    dataset->name = name;
    dataset->path = path;
    dataset->samplesOnRanks = true;
    dataset->frame = frame;
    describeRange(*dataset, summary.range);
    dataset->contentCrc = summary.contentCrc;
    dataset->volume = std::make_shared<fit::Volume>(
        fit::loadVolumePlanes(path.string(), 0, 0, std::nullopt, DATASET_STORAGE, {}, frame).whole);
    return dataset;
}

std::string plainName(const std::string& text) {
    std::string out = text;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
    return out;
}

/// The DICOM series of each subfolder, named as dicomDatasetNames says; a folder that cannot be read is
/// reported and left out, as an unreadable volume file would be when it is first used.
void addDicomFolders(const std::vector<fs::path>& folders,
                     std::map<std::string, std::pair<fs::path, std::string>>& found) {
    for (const fs::path& folder : folders) {
        std::vector<fit::DicomSeriesSummary> series;
        try {
            series = fit::listDicomSeries(folder.string());
        } catch (const std::exception& e) {
            std::cerr << "vots serve: warning: DICOM folder '" << folder.string() << "' skipped: " << e.what()
                      << "\n";
            continue;
        }
        for (const auto& [name, uid] : dicomDatasetNames(folder.filename().string(), series))
            found.emplace(name, std::make_pair(folder, series.size() > 1 ? uid : std::string()));
    }
}

} // namespace

std::map<std::string, std::string> dicomDatasetNames(const std::string& folderName,
                                                     const std::vector<fit::DicomSeriesSummary>& series) {
    std::map<std::string, std::string> names;
    if (series.size() == 1) names[plainName(folderName)] = series.front().uid;
    if (series.size() <= 1) return names;
    std::set<std::string> descriptions;
    for (const fit::DicomSeriesSummary& s : series)
        if (!s.description.empty()) descriptions.insert(plainName(s.description));
    const bool byDescription = descriptions.size() == series.size();
    for (const fit::DicomSeriesSummary& s : series) {
        const std::string suffix =
            byDescription ? s.description : s.uid.substr(s.uid.size() > 8 ? s.uid.size() - 8 : 0);
        names[plainName(folderName + "-" + suffix)] = s.uid;
    }
    return names;
}

std::map<std::string, render::DisplaySettings> windowPresets(std::array<float, 2> range, bool isCt) {
    const float lo = range[0];
    const float span = std::max(range[1] - range[0], 1e-6f);
    std::map<std::string, render::DisplaySettings> presets;
    presets["full"] = {lo + 0.5f * span, span};
    if (isCt) {
        presets["bone"] = {300.f, 1500.f}; // common radiology bone window
        presets["soft"] = {40.f, 400.f};   // common soft-tissue window
    } else {
        presets["bone"] = {lo + 0.75f * span, 0.5f * span}; // the upper half: dense structures
        presets["soft"] = {lo + 0.3f * span, 0.4f * span};  // low-mid values: faint structures
    }
    return presets;
}

DatasetRegistry::DatasetRegistry(const std::vector<fs::path>& dataDirs, MemoryAdmission& memory,
                                 std::uint64_t heldFrameBytes)
    : mMemory(memory), mHeldFrames(heldFrameBytes ? heldFrameBytes : memory.budget() / HELD_FRAMES_SHARE) {
    for (const fs::path& dir : dataDirs) {
        std::error_code ec;
        fs::directory_iterator it(dir, ec);
        if (ec) {
            std::cerr << "vots serve: warning: cannot read data folder '" << dir.string()
                      << "': " << ec.message() << "\n";
            continue;
        }
        std::vector<fs::path> files, folders;
        for (const auto& entry : it) {
            if (entry.is_regular_file(ec)) files.push_back(entry.path());
            if (entry.is_directory(ec)) folders.push_back(entry.path());
        }
        std::sort(files.begin(), files.end()); // deterministic choice when two files share a stem
        std::sort(folders.begin(), folders.end());
        for (const fs::path& file : files) {
            const std::string name = volumeStem(file);
            if (!isDatasetName(name) || mEntries.count(name)) continue;
            auto entry = std::make_unique<Entry>();
            entry->path = file;
            mEntries.emplace(name, std::move(entry));
        }
        std::map<std::string, std::pair<fs::path, std::string>> dicom;
        addDicomFolders(folders, dicom);
        for (auto& [name, where] : dicom) {
            if (!isDatasetName(name) || mEntries.count(name)) continue; // a volume file of that name wins
            auto entry = std::make_unique<Entry>();
            entry->path = where.first;
            entry->dicomSeries = where.second;
            mEntries.emplace(name, std::move(entry));
        }
        for (const fs::path& file : files) {
            const std::string name = votsStem(file);
            if (!isDatasetName(name) || mEntries.count(name)) continue; // a volume of that name wins
            auto entry = std::make_unique<Entry>();
            entry->path = file;
            entry->isVots = true;
            mEntries.emplace(name, std::move(entry));
        }
    }
}

void DatasetRegistry::offerDicomFolder(const std::string& name, const fs::path& folder) {
    if (!isDatasetName(name))
        throw HttpError(400, "dataset must be a plain name of letters, digits, '_' and '-'");
    Entry* entry = nullptr;
    {
        std::lock_guard lock(mMutex);
        auto& slot = mEntries[name];
        if (!slot) {
            slot = std::make_unique<Entry>();
            slot->path = folder;
            return;
        }
        entry = slot.get(); // entries are never removed, so the pointer stays valid
    }
    std::lock_guard loadLock(entry->loadMutex);
    if (entry->path == folder && entry->loadError.empty()) return;
    std::lock_guard lock(mMutex);
    entry->path = folder;
    entry->dicomSeries.clear();
    entry->isVots = false;
    entry->dataset.reset();
    entry->otherFrames.clear();
    mHeldFrames.forget(name);
    entry->header.reset();
    entry->loadError.clear();
}

void DatasetRegistry::offerLoadedDicomFolder(const std::string& name, const fs::path& folder,
                                             fit::Volume volume, const VolumeSummary& summary) {
    offerDicomFolder(name, folder);
    if (mRanks) return; // the ranks read the folder themselves
    Entry* entry = nullptr;
    {
        std::lock_guard lock(mMutex);
        entry = mEntries.at(name).get();
    }
    fit::VolumeHeaderInfo header;
    for (int a = 0; a < 3; ++a)
        header.dims[a] = static_cast<std::uint64_t>(volume.dims[a]);
    header.sourceType = volume.sourceType;
    std::lock_guard loadLock(entry->loadMutex);
    auto dataset =
        datasetOfVolume(name, folder, {}, header, std::make_shared<fit::Volume>(std::move(volume)), summary);
    std::lock_guard lock(mMutex);
    entry->header = header;
    entry->dataset = std::move(dataset);
}

std::vector<std::string> DatasetRegistry::names() const {
    std::lock_guard lock(mMutex);
    std::vector<std::string> out;
    for (const auto& [name, entry] : mEntries)
        out.push_back(name);
    return out;
}

void DatasetRegistry::rememberLoadFailure(Entry& entry, const std::string& name) {
    HttpFailure failure = classifyFailure(std::current_exception());
    // Over the memory budget, out of memory or ranks lost: asked again next time, as the client may.
    if (isRetryable(failure.status)) throw HttpError(failure.status, failure.message);
    // The file's own fault (malformed, unreadable): every later request gets the same 500.
    std::cerr << "vots serve: warning: dataset '" << name << "' cannot be loaded: " << failure.message
              << "\n";
    entry.loadError = std::move(failure.message);
}

std::shared_ptr<const Dataset> DatasetRegistry::find(const std::string& name, int frame) {
    if (!isDatasetName(name))
        throw HttpError(400, "dataset must be a plain name of letters, digits, '_' and '-'");
    Entry* entry = nullptr;
    {
        std::lock_guard lock(mMutex);
        const auto it = mEntries.find(name);
        if (it == mEntries.end()) throw HttpError(404, "unknown dataset '" + name + "'");
        entry = it->second.get(); // entries are never removed, so the pointer stays valid
    }
    std::lock_guard loadLock(entry->loadMutex);
    if (!entry->dataset && entry->loadError.empty() && entry->isVots) {
        try {
            // Sized from the file alone, refused before it is read, like a volume by its header.
            const MemoryReservation admitted = mMemory.admit(
                estimateVotsLoadBytes(fs::file_size(entry->path)),
                "dataset '" + name + "' (Vot-Space file '" + entry->path.filename().string() + "')");
            auto dataset = loadVotsDataset(name, entry->path);
            std::lock_guard lock(mMutex); // loaded() reads dataset under mMutex
            entry->dataset = std::move(dataset);
        } catch (...) {
            rememberLoadFailure(*entry, name);
        }
    }
    if (!entry->dataset && entry->loadError.empty()) {
        try {
            if (!entry->header) {
                auto header = fit::volumeHeaderInfo(entry->path.string(), std::nullopt, entry->dicomSeries);
                std::lock_guard lock(mMutex); // header() reads it under mMutex
                entry->header = header;
            }
            // Refused before anything is allocated. Admitted against load and fit together: a volume that
            // loads but cannot be fitted is of no use. Given back once loaded: the samples are then
            // resident, and each fit job is admitted for its own part (Dataset::fitBytes).
            const MemoryReservation admitted =
                mMemory.admit(mRanks ? 0 : fit::estimateLoadAndFitBytes(*entry->header, DATASET_STORAGE),
                              "dataset '" + name + "' (" + entry->header->describe() + ")");
            auto dataset = mRanks ? summarizeDataset(name, entry->path, entry->dicomSeries, *mRanks, 0)
                                  : loadDataset(name, entry->path, entry->dicomSeries, *entry->header, 0);
            dataset->frames = entry->header->frames;
            std::lock_guard lock(mMutex); // loaded() reads dataset under mMutex
            entry->dataset = std::move(dataset);
        } catch (...) {
            rememberLoadFailure(*entry, name);
        }
    }
    if (!entry->dataset) throw HttpError(500, "dataset '" + name + "' cannot be loaded: " + entry->loadError);
    return frame == 0 ? entry->dataset : findOtherFrame(*entry, name, frame);
}

std::shared_ptr<const Dataset> DatasetRegistry::findOtherFrame(Entry& entry, const std::string& name,
                                                               int frame) {
    const std::uint64_t frames = entry.dataset->frames;
    if (frame < 0 || static_cast<std::uint64_t>(frame) >= frames)
        throw HttpError(400, "dataset '" + name + "' has no frame " + std::to_string(frame) + ": it holds " +
                                 std::to_string(frames) + (frames == 1 ? " frame" : " frames"));
    const std::string what =
        "frame " + std::to_string(frame) + " of dataset '" + name + "' (" + entry.header->describe() + ")";
    // Under mpirun the ranks hold the samples (each its planes of the frame asked last) and this process
    // the grid alone.
    const std::uint64_t bytes = mRanks ? 0 : fit::estimateLoadedVolumeBytes(*entry.header, DATASET_STORAGE);
    const std::uint64_t admitBytes = mRanks ? 0 : entry.dataset->loadAndFitBytes;
    {
        std::lock_guard lock(mMutex);
        if (auto it = entry.otherFrames.find(frame); it != entry.otherFrames.end()) {
            mHeldFrames.touch(name, frame);
            return it->second;
        }
        // A frame still drawn or fitted is freed when that ends (the shared_ptr).
        mHeldFrames.makeRoom(
            bytes, [&] { return mMemory.refusal(admitBytes, what).empty(); },
            [this](const std::string& dataset, int dropped) {
                mEntries.at(dataset)->otherFrames.erase(dropped);
            });
    }
    // Admitted as frame 0 was: each frame is a volume of the same size, resident once loaded.
    const MemoryReservation admitted = mMemory.admit(admitBytes, what);
    auto dataset = mRanks ? summarizeDataset(name, entry.path, entry.dicomSeries, *mRanks, frame)
                          : loadDataset(name, entry.path, entry.dicomSeries, *entry.header, frame);
    dataset->frames = frames;
    std::lock_guard lock(mMutex); // loaded() reads the frames under mMutex
    entry.otherFrames.emplace(frame, dataset);
    mHeldFrames.add(name, frame, bytes);
    return dataset;
}

HeldFramesSummary DatasetRegistry::heldFrames() const {
    std::lock_guard lock(mMutex);
    return mHeldFrames.summary();
}

std::optional<fit::VolumeHeaderInfo> DatasetRegistry::header(const std::string& name) const {
    std::lock_guard lock(mMutex);
    const auto it = mEntries.find(name);
    if (it == mEntries.end()) return std::nullopt;
    return it->second->header;
}

DatasetKind DatasetRegistry::kind(const std::string& name) const {
    std::lock_guard lock(mMutex);
    const auto it = mEntries.find(name);
    return it != mEntries.end() && it->second->isVots ? DatasetKind::Vots : DatasetKind::Volume;
}

std::vector<std::shared_ptr<const Dataset>> DatasetRegistry::loaded() const {
    std::lock_guard lock(mMutex);
    std::vector<std::shared_ptr<const Dataset>> out;
    for (const auto& [name, entry] : mEntries) {
        if (entry->dataset) out.push_back(entry->dataset);
        for (const auto& [frame, dataset] : entry->otherFrames)
            out.push_back(dataset);
    }
    return out;
}

} // namespace vots::server
