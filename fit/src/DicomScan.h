// Private to the DICOM reader: what one file's header says, and a folder's DICOM images grouped by series.
#pragma once

#include "vots/fit/DicomSeries.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// The header fields of one DICOM image file that place and decode its slice.
struct DicomSliceHeader {
    std::string path;
    std::string seriesUid;
    std::string seriesDescription;
    int rows = 0;
    int columns = 0;
    int frames = 1;
    int samplesPerPixel = 1;
    int bitsAllocated = 0;
    int bitsStored = 0;
    bool pixelsSigned = false;
    bool hasPosition = false;                // ImagePositionPatient and ImageOrientationPatient both present
    std::array<double, 3> position{0, 0, 0}; // ImagePositionPatient
    std::array<double, 6> orientation{1, 0, 0, 0, 1, 0}; // ImageOrientationPatient: row, then column
    std::array<double, 2> pixelSpacing{1, 1};            // PixelSpacing: between rows, between columns
    double slope = 1.0;                                  // RescaleSlope
    double intercept = 0.0;                              // RescaleIntercept
    bool encapsulated = false;                           // compressed pixel data (JPEG, RLE, ...)
    std::uint64_t pixelDataOffset = 0;                   // where the pixel values start in the file
    std::uint64_t fileSize = 0;
    /// Orders the images of a 4D series at one position in time: TemporalPositionIdentifier, else
    /// AcquisitionTime (seconds of the day), else InstanceNumber; 0 when none is present.
    double timeOrder = 0.0;
};

class ChildSender;
class ParentReceiver;

/// The header of one file; nullopt for a file that is not a DICOM image (skipped). Throws InputError for
/// a DICOM file that cannot be parsed. GDCM may abort on a damaged file: call it in a child (DicomChild.h).
std::optional<DicomSliceHeader> readSliceHeader(const std::string& path);

/// In the child: sends what readSliceHeader gave (nullopt too) for receiveSliceHeader in the parent.
void sendSliceHeader(const std::optional<DicomSliceHeader>& slice, ChildSender& child);
/// In the parent: the header the child sent for the file at `path`.
std::optional<DicomSliceHeader> receiveSliceHeader(const std::string& path, ParentReceiver& parent);

/// Every DICOM image in the folder (not recursive), in file-name order; other files are skipped. GDCM
/// runs in a child process (DicomChild.h). Throws InputError for a folder that cannot be read, or a file
/// that starts like DICOM but cannot be parsed.
std::vector<DicomSliceHeader> scanDicomFolder(const std::string& folder);

/// Silences GDCM's own warnings and errors on stderr: every problem reaches the user as one InputError.
void quietGdcm();

} // namespace vots::fit::detail
