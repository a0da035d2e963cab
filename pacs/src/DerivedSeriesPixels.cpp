// The stored pixel values of a derived series: the rescale chosen for its range, and the storage class.
#include "DerivedSeriesFile.h"

#include <algorithm>
#include <cmath>

namespace vots::pacs {

namespace {
constexpr double LARGEST_STORED = 32767.0;
constexpr double WHOLE_UNITS_MIN_SPAN = 1000.0;
} // namespace

PixelRescale chooseRescale(double lo, double hi) {
    if (!(lo <= hi)) return {};
    if (lo >= -LARGEST_STORED && hi <= LARGEST_STORED && hi - lo >= WHOLE_UNITS_MIN_SPAN) return {};
    PixelRescale r;
    r.intercept = 0.5 * (lo + hi);
    // A constant image still needs a slope that is not 0; any positive one stores it as 0 exactly.
    r.slope = hi > lo ? (hi - lo) / (2.0 * LARGEST_STORED) : 1.0;
    return r;
}

std::string storageClassFor(const std::optional<fit::DicomIdentity>& source) {
    constexpr const char* CT_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.2";
    constexpr const char* MR_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.4";
    constexpr const char* SECONDARY_CAPTURE_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.7";
    if (source && source->modality == "CT") return CT_IMAGE_STORAGE;
    if (source && source->modality == "MR") return MR_IMAGE_STORAGE;
    return SECONDARY_CAPTURE_IMAGE_STORAGE;
}

namespace detail {

std::int16_t storedValue(float value, const PixelRescale& rescale) {
    if (!std::isfinite(value)) return PIXEL_PADDING;
    const double stored = std::round((static_cast<double>(value) - rescale.intercept) / rescale.slope);
    return static_cast<std::int16_t>(std::clamp(stored, -LARGEST_STORED, LARGEST_STORED));
}

} // namespace detail
} // namespace vots::pacs
