// Reading volumes from files: NRRD, NIfTI, MGH, MetaImage, raw, DICOM folders; throws InputError on bad
// input.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <optional>
#include <string>

namespace vots::fit {

/// Layout of a headerless raw file, given on the command line.
struct RawLayout {
    std::array<int, 3> dims{0, 0, 0};
    ScalarType type = ScalarType::UInt8;
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    bool bigEndian = false;
    std::size_t headerBytes = 0; // bytes to skip before the samples
};

/// How a loaded volume holds its samples.
enum class SampleStorage {
    Float, // Volume::values, whatever the file's type
    Source // Volume::compact for 8- and 16-bit integer files (a half or a quarter of the memory), else
           // values; fitting either gives the same Vots
};

/// Parses "int16", "uint8", "float32", ... (also "short", "float", "uchar"); throws InputError.
ScalarType parseScalarType(const std::string& text);

/// Loads a volume. The format follows the extension: .nrrd/.nhdr, .nii/.nii.gz (NIfTI-1 and -2),
/// .mgh/.mgz (FreeSurfer), .mhd/.mha; with a raw layout any file is read as raw samples; a folder is read
/// as a DICOM series (loadDicomSeries in DicomSeries.h), `dicomSeries` picking one by UID when it holds
/// several. `frame` (0-based) picks one 3D volume of a 4D NIfTI or MGH file or of a DICOM series with
/// several images at each position (loadDicomSeries); every other file has only frame 0. Throws InputError
/// with a one-line message (a frame out of range names the frame count).
Volume loadVolume(const std::string& path, const std::optional<RawLayout>& raw = std::nullopt,
                  SampleStorage storage = SampleStorage::Float, const std::string& dicomSeries = {},
                  int frame = 0);

Volume loadNrrd(const std::string& path, SampleStorage storage = SampleStorage::Float);
Volume loadNifti(const std::string& path, SampleStorage storage = SampleStorage::Float, int frame = 0);
Volume loadMgh(const std::string& path, SampleStorage storage = SampleStorage::Float, int frame = 0);
Volume loadMetaImage(const std::string& path, SampleStorage storage = SampleStorage::Float);
Volume loadRaw(const std::string& path, const RawLayout& layout,
               SampleStorage storage = SampleStorage::Float);

} // namespace vots::fit
