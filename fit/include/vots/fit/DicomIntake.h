// Reading a DICOM series while its files are still arriving (a retrieve from a PACS), so that the read
// overlaps the transfer instead of following it.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace vots::fit {

/// What the intake made of the files it was given.
struct DicomIntakeResult {
    /// The series as loadDicomSeries gives it from a folder of these files, named `name`; nullopt when
    /// the files are not the announced grid (another image size, sample type or count): read them as a
    /// folder then, which names the problem.
    std::optional<Volume> volume;
    /// With a volume: its contentCrc() and valueRange(), combined from each slice's as it arrived.
    std::uint32_t contentCrc = 0;
    std::array<float, 2> valueRange{0.f, 0.f};
    int images = 0; // files that were DICOM images
    int files = 0;  // files added
};

/// Each file added is read by GDCM in one child process under the DICOM reader's limits (address space,
/// time) as soon as it is added, and its rescaled slice stored in samples allocated once for the
/// announced grid; finish() puts the slices in the order of their positions. Files of a damaged series
/// fail as loadDicomSeries fails on them (InputError naming the file).
class DicomSeriesIntake {
public:
    /// `announced`: the series' dims (columns, rows, instances) and the type its samples load into.
    DicomSeriesIntake(const VolumeHeaderInfo& announced, SampleStorage storage);
    /// Without finish() (a cut retrieve): stops the child and frees the samples.
    ~DicomSeriesIntake();
    DicomSeriesIntake(const DicomSeriesIntake&) = delete;
    DicomSeriesIntake& operator=(const DicomSeriesIntake&) = delete;

    /// One more file of the series, complete on disk. Thread-safe; never blocks on the decoding.
    void add(const std::string& path);
    /// No more files: waits for the last one and orders the slices. Throws InputError for a damaged file.
    DicomIntakeResult finish(const std::string& name);

private:
    struct State;
    std::unique_ptr<State> mState;
};

} // namespace vots::fit
