// The datasets the server offers (volumes and Vot-Space files): found by name in the data folders, loaded
// lazily once, then kept.
#pragma once

#include "datasets/HeldFrames.h"
#include "datasets/MemoryAdmission.h"

#include "vots/dist/FrameRanks.h"
#include "vots/fit/DicomSeries.h"
#include "vots/fit/EnumNames.h"
#include "vots/fit/Volume.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VotSpace.h"
#include "vots/render/DisplaySettings.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace vots::server {

/// What a dataset was loaded from: a volume (fitted on demand at any eps), or a .vots file (its one
/// Vot-Space; no grid for reference frames, no refit).
enum class DatasetKind { Volume, Vots };

/// The API's names of the kinds.
inline constexpr auto DATASET_KIND_NAMES = fit::nameTable<DatasetKind>(
    "dataset kind", {{DatasetKind::Volume, "volume"}, {DatasetKind::Vots, "vots"}});
constexpr const auto& namesOf(DatasetKind) {
    return DATASET_KIND_NAMES;
}

/// A loaded volume or Vot-Space plus what the API reports about it.
struct Dataset {
    std::string name;           // file stem, a plain identifier
    std::filesystem::path path; // the file it came from
    std::string dicomSeries;    // the SeriesInstanceUID when `path` is a DICOM folder of several series
    int frame = 0;              // which 3D volume of a 4D file `volume` is (0-based)
    std::uint64_t frames = 1;   // the 3D volumes the file holds (fMRI, perfusion, cardiac phases)
    DatasetKind kind = DatasetKind::Volume;
    std::shared_ptr<const fit::Volume> volume; // Volume kind only; null for Vots
    std::shared_ptr<const fit::VotSpace>
        space; // Vots kind only: the file's Vot-Space, placed in patient space
    std::array<float, 2> range{0,
                               0}; // min and max sample, data units (Vots: the source's, from the meta block)
    float background = 0.f;        // fit::defaultBackground(volume)
    std::uint32_t contentCrc = 0;  // volume->contentCrc()
    float defaultEps = 0.f;        // fit::EpsSpec{} resolved, data units (Vots: the file's eps, the only one)
    bool isCt = false;             // range looks like Hounsfield units (min <= -900)
    std::map<std::string, render::DisplaySettings> presets; // "bone", "soft", "full" (grey)
    std::uint64_t loadAndFitBytes = 0;                      // fit::estimateLoadAndFitBytes of its header
    std::uint64_t fitBytes = 0; // what one fit needs beyond the loaded volume (admitted per fit job)
    /// Under mpirun: `volume` is the grid alone (no samples), which stay with the ranks; range and CRC are
    /// theirs (dist::FrameRanks::summarize), and every fit happens on them.
    bool samplesOnRanks = false;
};

/// How the server holds a study's samples: in the file's 8- or 16-bit type where it has one (a half or a
/// quarter of floats' memory); the loads, fits, CRCs and grid images are those of float samples.
inline constexpr fit::SampleStorage DATASET_STORAGE = fit::SampleStorage::Source;

/// Window presets for a value range: HU presets when it looks like CT, else fractions of the range.
std::map<std::string, render::DisplaySettings> windowPresets(std::array<float, 2> range, bool isCt);

/// Memory a .vots file of this size takes while it loads and stays resident: its bytes, read whole,
/// plus the decoded Vots (one fit::Vot per 120-byte record).
std::uint64_t estimateVotsLoadBytes(std::uint64_t fileBytes);

/// Thread-safe. Scans the folders once at construction for .nrrd/.nhdr/.nii/.nii.gz/.mgh/.mgz/.mhd/.mha
/// files, for subfolders holding DICOM series (dicomDatasetNames) and for .vots files; the first folder that
/// has a name wins, and within a folder a volume file wins over a DICOM folder, which wins over a .vots file.
/// Loading happens on the first find() of a name, once `memory` admits the load and fit its header announces.
/// The datasets of one DICOM folder, name -> SeriesInstanceUID: the folder's name for a single series;
/// for several, "<folder>-<description>" when every series has a distinct description, else
/// "<folder>-<last 8 characters of the UID>" (characters other than letters, digits, '_' and '-' become
/// '_'). Reads headers only; empty when the folder holds no DICOM images.
std::map<std::string, std::string> dicomDatasetNames(const std::string& folderName,
                                                     const std::vector<fit::DicomSeriesSummary>& series);

/// What a reader may give with a volume so that it is not read again for them.
struct VolumeSummary {
    std::array<float, 2> valueRange{0.f, 0.f}; // fit::Volume::valueRange()
    std::uint32_t contentCrc = 0;              // fit::Volume::contentCrc()
};

class DatasetRegistry {
public:
    /// `heldFrameBytes`: frames of 4D datasets other than frame 0 stay loaded within this many bytes
    /// (0: a quarter of the memory budget), least recently used dropped first.
    DatasetRegistry(const std::vector<std::filesystem::path>& dataDirs, MemoryAdmission& memory,
                    std::uint64_t heldFrameBytes = 0);
    /// From now on a volume dataset is summarized by the ranks (samplesOnRanks), not loaded here: this
    /// process holds none of its samples. Call before the first find().
    void summarizeOnRanks(dist::FrameRanks* ranks) { mRanks = ranks; }

    /// Adds a DICOM folder of one series (a series retrieved from a PACS) under `name`, loaded on its
    /// first find() like the data folders' own. When `name` is already offered from another folder (the
    /// series changed on the PACS), it is read from `folder` from now on.
    void offerDicomFolder(const std::string& name, const std::filesystem::path& folder);
    /// The same with the folder's series read already (as its files arrived from the PACS), in
    /// DATASET_STORAGE, and `summary` its valueRange() and contentCrc(): find() answers it without
    /// reading the folder or the samples again.
    void offerLoadedDicomFolder(const std::string& name, const std::filesystem::path& folder,
                                fit::Volume volume, const VolumeSummary& summary);

    /// All names found, sorted.
    std::vector<std::string> names() const;
    /// The dataset, loading it on first use. Throws HttpError 400 for a name that is not a plain
    /// identifier, 404 for an unknown one, 500 when the file cannot be read (the reason is kept), 507
    /// when its header announces more than the memory budget leaves (asked again next time: memory may
    /// have been freed meanwhile). `frame` picks one 3D volume of a 4D file, loaded on its first use as
    /// frame 0 is (which is loaded first: it says how many the file holds); a frame the file does not hold
    /// is a 400 naming the count.
    std::shared_ptr<const Dataset> find(const std::string& name, int frame = 0);
    /// The header of a dataset find() has looked at, loaded or not (nullopt before, or when unreadable).
    std::optional<fit::VolumeHeaderInfo> header(const std::string& name) const;
    /// Whether a name found is a volume or a .vots file, loaded or not (Volume for an unknown name).
    DatasetKind kind(const std::string& name) const;
    /// Already loaded datasets only (never loads), for stats.
    std::vector<std::shared_ptr<const Dataset>> loaded() const;
    /// The frames other than frame 0 held now.
    HeldFramesSummary heldFrames() const;

private:
    struct Entry {
        std::filesystem::path path;
        std::string dicomSeries; // the SeriesInstanceUID when `path` is a folder holding several
        bool isVots = false;     // `path` is a Vot-Space file
        std::mutex loadMutex;    // held while this one file loads, so others load in parallel
        std::shared_ptr<const Dataset> dataset; // frame 0
        // Of a 4D file, as they are asked for, while mHeldFrames keeps them; under mMutex.
        std::map<int, std::shared_ptr<const Dataset>> otherFrames;
        std::optional<fit::VolumeHeaderInfo> header; // read before loading; written under mMutex
        std::string loadError;
    };
    /// In a catch block of a load: passes on a failure the client may retry (classifyFailure: 503, 507),
    /// remembers any other as the file's, so that every later request is answered 500 with it.
    static void rememberLoadFailure(Entry& entry, const std::string& name);
    /// Frame `frame` (> 0) of a 4D volume whose frame 0 is loaded; under the entry's loadMutex.
    std::shared_ptr<const Dataset> findOtherFrame(Entry& entry, const std::string& name, int frame);
    MemoryAdmission& mMemory;
    dist::FrameRanks* mRanks = nullptr;
    mutable std::mutex mMutex;
    std::map<std::string, std::unique_ptr<Entry>> mEntries;
    HeldFrames mHeldFrames; // the entries' otherFrames in the order of use; under mMutex
};

} // namespace vots::server
