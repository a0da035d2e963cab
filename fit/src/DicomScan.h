// Private to the DICOM reader: what one file's header says, and a folder's DICOM images grouped by series.
#pragma once

#include "vots/fit/DicomSeries.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// Where the PerFrameFunctionalGroupsSequence of a multi-frame instance puts one of its frames.
struct FramePlace {
    int hasPosition = 0;                 // PlanePositionSequence > ImagePositionPatient present
    double position[3]{};                // ImagePositionPatient
    int hasTime = 0;                     // FrameContentSequence > TemporalPositionIndex present
    double timeOrder = 0.0;              // that index
    double slope = 1.0, intercept = 0.0; // PixelValueTransformationSequence, else the file's
};

/// The header fields of one DICOM image file that place and decode its slice; for a multi-frame instance
/// (frames > 1) the file's header, which layoutOfSlices turns into one such header per frame.
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
    int frameIndex = 0;    // which frame of its file this header places (0 for single-frame files)
    double frameGap = 0.0; // SpacingBetweenSlices, else SliceThickness: between the frames of a stack
    /// One per frame when the functional groups place the frames; empty otherwise (the frames then stack
    /// along the normal, frameGap apart, from the file's position).
    std::vector<FramePlace> framePlaces;
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
