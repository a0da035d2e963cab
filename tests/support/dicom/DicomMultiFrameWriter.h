// Test-data writer: volumes as one multi-frame DICOM instance (Enhanced CT style) through GDCM.
#pragma once

#include "vots/fit/Volume.h"

#include <array>
#include <string>
#include <vector>

namespace vots::test {

struct MultiFrameOptions {
    std::string seriesUid = "1.2.826.0.1.3680043.10.1234.2";
    /// Each frame's ImagePositionPatient in a PerFrameFunctionalGroupsSequence item (and the position,
    /// orientation, pixel spacing and rescale in the shared groups, none at the top level, as Enhanced CT
    /// writes them); false: no functional groups, the frames stack at SpacingBetweenSlices from the top-level
    /// position.
    bool functionalGroups = true;
    /// Frames in file order: all slices of time point 0, then of time point 1, ...; with true, slices are
    /// written from the highest position down (the reader must order by position, not by frame number).
    bool slicesDescending = false;
    std::array<double, 3> origin{-20, 10, 35};
    double intercept = -1024.0;      // stored = value - intercept, int16
    int announcedFrames = 0;         // > 0: NumberOfFrames says this instead (a damaged header)
    std::string syntax = "explicit"; // explicit or rle
};

/// Writes `timePoints` (one Volume per time point, same grid; slice z of each at origin + z * spacing[2]
/// along the axial normal) as one file of slices x timePoints frames; each frame's FrameContentSequence holds
/// TemporalPositionIndex t + 1 when there are several time points. Throws std::runtime_error.
void writeMultiFrameDicom(const std::vector<fit::Volume>& timePoints, const std::string& path,
                          const MultiFrameOptions& options);

} // namespace vots::test
