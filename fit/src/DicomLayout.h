// Private to the DICOM reader: one series of a folder checked and ordered into a grid, from headers only.
#pragma once

#include "DicomScan.h"

#include "vots/fit/Volume.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// A series as a grid: its slices in the order of increasing position along the slice normal.
struct DicomSeriesLayout {
    std::vector<DicomSliceHeader> slices;
    std::array<int, 3> dims{0, 0, 0};                   // columns, rows, slices
    std::array<double, 3> spacing{1, 1, 1};             // between columns, rows, slice positions
    std::array<double, 3> origin{0, 0, 0};              // ImagePositionPatient of the first slice
    std::array<std::array<double, 3>, 3> patientAxes{}; // row direction, column direction, normal
    ScalarType valueType = ScalarType::Float32;         // the smallest type that holds every rescaled value
    std::uint64_t frames = 1; // images at each position: time points of a 4D series, of which `slices` is one
};

/// Picks the series (`seriesUid`, or the only one) and checks that it forms a grid: one image size, one
/// orientation, evenly spaced positions. A 4D series holds as many images at every position (one per time
/// point, ordered by DicomSliceHeader::timeOrder): `frame` picks the time point whose images the layout
/// keeps; a frame it does not hold is an InputError naming the count. Throws InputError with one line
/// naming the problem.
DicomSeriesLayout layoutDicomSeries(const std::string& folder, const std::string& seriesUid, int frame = 0);

/// The same for the headers of one series' files, read already; `folder` names where they are in messages.
DicomSeriesLayout layoutOfSlices(std::vector<DicomSliceHeader> slices, const std::string& folder,
                                 int frame = 0);

/// The smallest type that holds every rescaled value of these slices: integral rescales keep integer
/// samples integral, so a 12-bit CT with intercept -1024 stays int16 (the memory of `vots fit` stays low).
ScalarType valueTypeOf(const std::vector<DicomSliceHeader>& slices);

/// The series' grid as loadDicomSeries gives it (named after the folder), without samples.
Volume gridOfLayout(const DicomSeriesLayout& layout, const std::string& folder);

} // namespace vots::fit::detail
