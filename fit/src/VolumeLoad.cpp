// Picks the volume reader from the file extension (or the raw layout); the readers do the parsing.
#include "vots/fit/VolumeLoad.h"

#include "InputFile.h"

#include "vots/fit/DicomSeries.h"

namespace vots::fit {

Volume loadVolume(const std::string& path, const std::optional<RawLayout>& raw, SampleStorage storage,
                  const std::string& dicomSeries) {
    if (raw) return loadRaw(path, *raw, storage);
    if (isDicomFolder(path)) return loadDicomSeries(path, dicomSeries, storage);
    const std::string extension = detail::volumeExtension(path);
    if (extension == ".nrrd" || extension == ".nhdr") return loadNrrd(path, storage);
    if (extension == ".nii" || extension == ".nii.gz") return loadNifti(path, storage);
    if (extension == ".mhd" || extension == ".mha") return loadMetaImage(path, storage);
    detail::throwUnknownVolumeFormat(path);
}

} // namespace vots::fit
