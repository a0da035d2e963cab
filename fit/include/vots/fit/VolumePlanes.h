// Runs of z planes of a volume: cut from a loaded one, or read from the file without the other planes.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeLoad.h"

#include <optional>
#include <string>

namespace vots::fit {

/// Planes [first, last] along z (the slowest axis) of a loaded volume, held as it holds them (floats or
/// compact), with the origin moved to plane `first`. Throws InputError unless 0 <= first <= last < dims z.
Volume planesOf(const Volume& volume, int first, int last);

/// True when loadVolumePlanes holds only the planes' samples: read by offset from NRRD with raw encoding
/// (attached, detached or several data files), NIfTI .nii, MGH .mgh, MetaImage without CompressedData and raw
/// layouts; decompressed from the start of a gzip NRRD's streams, a NIfTI .nii.gz or an MGH .mgz, keeping
/// only the planes' bytes and stopping after them; a DICOM series decodes only the planes' slice files.
/// MetaImage's CompressedData is loaded whole and cut. Reads the header only; throws InputError as
/// loadVolume does.
bool readsOnlyPlanes(const std::string& path, const std::optional<RawLayout>& raw = std::nullopt);

/// A run of planes of a volume file, and the grid of the whole volume they belong to.
struct PlanesOfGrid {
    Volume planes;
    Volume whole; // dims, spacing, origin, axes, type and name of the whole volume; no samples
};

/// The whole volume's grid (as loadVolume would give it) without its samples.
Volume gridOf(const Volume& volume);

/// Planes [first, last] of the volume loadVolume would give: the same result as planesOf(loadVolume(...),
/// first, last), bit for bit, read alone where readsOnlyPlanes says so; `frame` as in loadVolume. Throws
/// InputError for bad input or planes outside the grid.
PlanesOfGrid loadVolumePlanes(const std::string& path, int first, int last,
                              const std::optional<RawLayout>& raw = std::nullopt,
                              SampleStorage storage = SampleStorage::Float,
                              const std::string& dicomSeries = {}, int frame = 0);

} // namespace vots::fit
