// Test-data writer: a Volume as a folder of single-slice CT DICOM files through GDCM, good or broken.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <string>

namespace vots::test {

/// Which file name (and InstanceNumber) each slice gets: the reader must order by position, not by these.
enum class DicomFileOrder {
    Ascending,  // slice-0001 is the lowest position along the normal
    Descending, // slice-0001 is the highest (as scanners that list head-first write a feet-to-head stack)
    Shuffled    // a fixed pseudo-random permutation
};

struct DicomWriteOptions {
    std::string seriesUid = "1.2.826.0.1.3680043.10.1234.1";
    std::string description = "synthetic";
    std::string patientId = "VOTS-PHANTOM-1";
    std::string frameOfReferenceUid = "1.2.826.0.1.3680043.10.1234.900";
    /// explicit, implicit, rle, jpeg-lossless, jpeg-ls or jpeg2000 (all lossless).
    std::string syntax = "explicit";
    DicomFileOrder order = DicomFileOrder::Ascending;
    std::string filePrefix = "slice"; // files are <prefix>-0001.dcm, ...
    bool storeSigned = true;          // int16 pixels, else uint16
    int bitsStored = 16;              // 12 for the usual unsigned CT
    double slope = 1.0;               // stored = round((value - intercept) / slope)
    double intercept = 0.0;
    std::array<double, 6> orientation{1, 0, 0, 0, 1, 0}; // ImageOrientationPatient (row, column)
    std::array<double, 3> origin{0, 0, 0};               // ImagePositionPatient of slice z = 0
    // Slice z sits at origin + z * spacing[2] * normal, or against the normal (row x column) when false:
    // a grid whose third axis runs against the right-handed normal (left-handed storage) needs it.
    bool slicesAlongNormal = true;
    // > 0: every slice is of this time point of a 4D series (TemporalPositionIdentifier, also in the SOP
    // instance UIDs); the series' other time points are written with the same seriesUid and another prefix.
    int temporalPosition = 0;
    // Broken series for the error tests; -1: none.
    int dropSlice = -1;     // this slice is not written (a gap in the positions)
    int resizeSlice = -1;   // this slice is one column narrower
    int truncateSlice = -1; // this slice's file is cut in the middle of its pixel data
    bool junkFile = false;  // also writes README.txt, which the reader must skip
};

/// Writes volume slice z (x fastest: columns, then rows) as one file per slice at position
/// origin + z * spacing[2] * (+-normal), PixelSpacing spacing[1]\spacing[0]. Throws std::runtime_error.
void writeDicomSeries(const fit::Volume& volume, const std::string& folder, const DicomWriteOptions& options);

} // namespace vots::test
