// Reading a folder of DICOM files as one volume (a series), through GDCM; throws InputError on bad series.
#pragma once

#include "vots/fit/Volume.h"
#include "vots/fit/VolumeHeader.h"
#include "vots/fit/VolumeLoad.h"

#include <string>
#include <vector>

namespace vots::fit {

/// Who and what a series belongs to: the patient, study and frame of reference modules of its first file
/// (in file-name order), as text with the padding removed; empty where the file leaves a tag out. A
/// series derived from it (pacs::writeDerivedSeries) joins the same patient and study.
struct DicomIdentity {
    std::string patientId;              // (0010,0020)
    std::string patientName;            // (0010,0010)
    std::string patientBirthDate;       // (0010,0030)
    std::string patientSex;             // (0010,0040)
    std::string studyInstanceUid;       // (0020,000D)
    std::string studyId;                // (0020,0010)
    std::string studyDate;              // (0008,0020)
    std::string studyTime;              // (0008,0030)
    std::string accessionNumber;        // (0008,0050)
    std::string referringPhysicianName; // (0008,0090)
    std::string studyDescription;       // (0008,1030)
    std::string modality;               // (0008,0060)
    std::string frameOfReferenceUid;    // (0020,0052)
    std::string manufacturer;           // (0008,0070)
};

/// One series found in a folder, from the files' headers only.
struct DicomSeriesSummary {
    std::string uid;         // SeriesInstanceUID
    std::string description; // SeriesDescription, may be empty
    int sliceCount = 0;      // image files of the series
};

/// True for a path that is a folder: every volume entry point reads a folder as a DICOM series.
bool isDicomFolder(const std::string& path);

/// The series of the folder's DICOM images (files that are not DICOM images are skipped), sorted by UID.
/// Reads headers only. Throws InputError for a folder that cannot be read or holds a damaged DICOM file.
std::vector<DicomSeriesSummary> listDicomSeries(const std::string& folder);

/// The grid and the sample type the series loads into, from the headers alone (rows x columns x slices,
/// bits, rescale), so memory admission can size it before anything is allocated. `seriesUid` picks a
/// series; empty: the folder must hold exactly one. Throws InputError with one line naming the problem
/// (no images, several series, missing slice, mixed image sizes, ...).
VolumeHeaderInfo dicomSeriesHeaderInfo(const std::string& folder, const std::string& seriesUid = {});

/// The identity of the series `seriesUid` (empty: the folder's only series) from the header of its first
/// file, read by GDCM in a child process. Throws InputError as dicomSeriesHeaderInfo does.
DicomIdentity readDicomIdentity(const std::string& folder, const std::string& seriesUid = {});

/// The type the samples of images with this pixel format and rescale load into: the smallest that holds
/// every rescaled value; integral rescales stay integers (a 12-bit CT with intercept -1024 stays int16).
ScalarType dicomSampleType(int bitsStored, bool pixelsSigned, double slope, double intercept);

/// Loads the series: values in real units (RescaleSlope/Intercept), slices ordered by
/// ImagePositionPatient along the slice normal, spacing from PixelSpacing and the slice positions,
/// orientation from ImageOrientationPatient. Compressed transfer syntaxes GDCM decodes are read. A series
/// with as many images at every position (a 4D series: perfusion, cardiac phases) holds one frame per time
/// point, ordered by TemporalPositionIdentifier, else AcquisitionTime, else InstanceNumber; `frame` picks
/// one (dicomSeriesHeaderInfo says how many).
Volume loadDicomSeries(const std::string& folder, const std::string& seriesUid = {},
                       SampleStorage storage = SampleStorage::Float, int frame = 0);

/// Slices [first, last] of what loadDicomSeries gives, bit for bit, with the origin at slice `first`:
/// every file's header is read to order the series, but only those slices' pixels are decoded, so a
/// rank of `mpirun vots fit` holds its slab alone. `grid` receives the whole series' grid, without
/// samples. Throws InputError as loadDicomSeries does, and for slices outside the series.
Volume loadDicomSeriesPlanes(const std::string& folder, int first, int last, Volume& grid,
                             const std::string& seriesUid = {}, SampleStorage storage = SampleStorage::Float,
                             int frame = 0);

} // namespace vots::fit
