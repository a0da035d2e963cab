// Picks the volume reader from the file extension (or the raw layout); the readers do the parsing.
#include "vots/fit/VolumeLoad.h"

#include "InputFile.h"

#include "vots/fit/DicomSeries.h"

namespace vots::fit {

Volume loadVolume(const std::string& path, const std::optional<RawLayout>& raw, SampleStorage storage,
                  const std::string& dicomSeries, int frame) {
    const std::string extension = raw || isDicomFolder(path) ? std::string() : detail::volumeExtension(path);
    if (extension == ".nii" || extension == ".nii.gz") return loadNifti(path, storage, frame);
    if (extension == ".mgh" || extension == ".mgz") return loadMgh(path, storage, frame);
    if (isDicomFolder(path) && !raw) return loadDicomSeries(path, dicomSeries, storage, frame);
    detail::checkFrame(path, frame, 1); // the other formats hold one 3D volume
    if (raw) return loadRaw(path, *raw, storage);
    if (extension == ".nrrd" || extension == ".nhdr") return loadNrrd(path, storage);
    if (extension == ".mhd" || extension == ".mha") return loadMetaImage(path, storage);
    detail::throwUnknownVolumeFormat(path);
}

} // namespace vots::fit
