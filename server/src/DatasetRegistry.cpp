// DatasetRegistry: finds volume files by stem, loads each once on demand, derives window presets.
#include "DatasetRegistry.h"

#include "HttpError.h"
#include "Params.h"
#include "vots/fit/Error.h"
#include "vots/fit/Fitter.h"
#include "vots/fit/MemoryBudget.h"
#include "vots/fit/VolumeLoad.h"

#include <algorithm>
#include <iostream>

namespace vots::server {
namespace fs = std::filesystem;
namespace {

constexpr float CT_MIN_HU = -900.f; // air is about -1000 HU; a minimum this low means CT

/// The dataset name of a file ("cranium" for cranium.nhdr or cranium.nii.gz), empty if not a volume.
std::string volumeStem(const fs::path& file) {
    const std::string name = file.filename().string();
    for (const char* ext : {".nii.gz", ".nrrd", ".nhdr", ".nii", ".mhd", ".mha"}) {
        const std::string e = ext;
        if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0)
            return name.substr(0, name.size() - e.size());
    }
    return {};
}

std::shared_ptr<const Dataset> loadDataset(const std::string& name, const fs::path& path,
                                           const fit::VolumeHeaderInfo& header) {
    auto volume = std::make_shared<fit::Volume>(fit::loadVolume(path.string()));
    auto dataset = std::make_shared<Dataset>();
    dataset->loadAndFitBytes = fit::estimateLoadAndFitBytes(header);
    const std::uint64_t held = fit::estimateLoadedVolumeBytes(header);
    dataset->fitBytes = dataset->loadAndFitBytes > held ? dataset->loadAndFitBytes - held : 0;
    dataset->name = name;
    dataset->path = path;
    dataset->range = volume->valueRange();
    dataset->background = fit::defaultBackground(*volume);
    dataset->contentCrc = volume->contentCrc();
    dataset->defaultEps = static_cast<float>(fit::EpsSpec{}.resolve(dataset->range[0], dataset->range[1]));
    dataset->isCt = dataset->range[0] <= CT_MIN_HU;
    dataset->presets = windowPresets(dataset->range, dataset->isCt);
    dataset->volume = std::move(volume);
    return dataset;
}

} // namespace

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

DatasetRegistry::DatasetRegistry(const std::vector<fs::path>& dataDirs, MemoryAdmission& memory)
    : mMemory(memory) {
    for (const fs::path& dir : dataDirs) {
        std::error_code ec;
        fs::directory_iterator it(dir, ec);
        if (ec) {
            std::cerr << "vots serve: warning: cannot read data folder '" << dir.string()
                      << "': " << ec.message() << "\n";
            continue;
        }
        std::vector<fs::path> files;
        for (const auto& entry : it)
            if (entry.is_regular_file(ec)) files.push_back(entry.path());
        std::sort(files.begin(), files.end()); // deterministic choice when two files share a stem
        for (const fs::path& file : files) {
            const std::string name = volumeStem(file);
            if (!isDatasetName(name) || mEntries.count(name)) continue;
            auto entry = std::make_unique<Entry>();
            entry->path = file;
            mEntries.emplace(name, std::move(entry));
        }
    }
}

std::vector<std::string> DatasetRegistry::names() const {
    std::lock_guard lock(mMutex);
    std::vector<std::string> out;
    for (const auto& [name, entry] : mEntries)
        out.push_back(name);
    return out;
}

std::shared_ptr<const Dataset> DatasetRegistry::find(const std::string& name) {
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
    if (!entry->dataset && entry->loadError.empty()) {
        try {
            if (!entry->header) {
                auto header = fit::volumeHeaderInfo(entry->path.string());
                std::lock_guard lock(mMutex); // header() reads it under mMutex
                entry->header = header;
            }
            // Refused before anything is allocated. Admitted against load and fit together: a volume that
            // loads but cannot be fitted is of no use. Given back once loaded: the samples are then
            // resident, and each fit job is admitted for its own part (Dataset::fitBytes).
            const MemoryReservation admitted =
                mMemory.admit(fit::estimateLoadAndFitBytes(*entry->header),
                              "dataset '" + name + "' (" + entry->header->describe() + ")");
            auto dataset = loadDataset(name, entry->path, *entry->header);
            std::lock_guard lock(mMutex); // loaded() reads dataset under mMutex
            entry->dataset = std::move(dataset);
        } catch (const HttpError&) {
            throw;                          // over the memory budget now; not remembered as a load error
        } catch (const std::exception& e) { // InputError for a malformed file, bad_alloc for a huge one
            entry->loadError = e.what();
            std::cerr << "vots serve: warning: dataset '" << name << "' cannot be loaded: " << e.what()
                      << "\n";
        }
    }
    if (!entry->dataset) throw HttpError(500, "dataset '" + name + "' cannot be loaded: " + entry->loadError);
    return entry->dataset;
}

std::optional<fit::VolumeHeaderInfo> DatasetRegistry::header(const std::string& name) const {
    std::lock_guard lock(mMutex);
    const auto it = mEntries.find(name);
    if (it == mEntries.end()) return std::nullopt;
    return it->second->header;
}

std::vector<std::shared_ptr<const Dataset>> DatasetRegistry::loaded() const {
    std::lock_guard lock(mMutex);
    std::vector<std::shared_ptr<const Dataset>> out;
    for (const auto& [name, entry] : mEntries)
        if (entry->dataset) out.push_back(entry->dataset);
    return out;
}

} // namespace vots::server
