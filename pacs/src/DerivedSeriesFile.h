// Private to the derived series writer: one image of the series as the bytes of a DICOM Part 10 file.
#pragma once

#include "vots/pacs/DerivedSeries.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vots::pacs::detail {

/// What the files of one series share beyond the DerivedSeries itself: the UIDs made for it and the
/// moment it was made (DICOM DA and TM text).
struct SeriesStamp {
    std::string studyInstanceUid;
    std::string seriesInstanceUid;
    std::string frameOfReferenceUid;
    std::string date; // YYYYMMDD
    std::string time; // HHMMSS
    PixelRescale rescale;
};

/// `image`, number `index` (from 0) of the series, as a DICOM file (explicit VR little endian) with
/// SOPInstanceUID `sopUid`; the series' own `images` are not read.
std::vector<std::uint8_t> encodeDerivedImage(const DerivedSeries& series, const DerivedImage& image,
                                             int index, const SeriesStamp& stamp, const std::string& sopUid);

/// The stored value of a pixel: the value through `rescale`, rounded and clamped to [-32767, 32767], or
/// PIXEL_PADDING when it is not finite.
std::int16_t storedValue(float value, const PixelRescale& rescale);

} // namespace vots::pacs::detail
