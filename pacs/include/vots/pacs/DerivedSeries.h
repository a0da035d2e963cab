// A derived DICOM series (e.g. thick-slab MIPs) written for a PACS: float images in the source's units
// with their patient-space geometry, joined to the source's patient and study.
#pragma once

#include "vots/fit/DicomSeries.h"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vots::pacs {

/// One image of the series: values in the source's units (HU for a CT), row 0 the top row, x to the
/// right; a pixel that is not finite has no value (outside the volume) and is stored as PIXEL_PADDING.
struct DerivedImage {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;                       // width * height, top row first
    std::array<double, 3> firstPixelCentre{0, 0, 0}; // ImagePositionPatient: the top left pixel, LPS mm
};

/// What every image of the series shares, in patient coordinates (LPS, mm).
struct DerivedGeometry {
    std::array<double, 3> rowDirection{1, 0, 0};    // unit vector along a row (image right)
    std::array<double, 3> columnDirection{0, 1, 0}; // unit vector down a column
    double pixelSpacingMm = 1.0;                    // square pixels
    double sliceThicknessMm = 1.0;
    double spacingBetweenSlicesMm = 1.0;
};

struct DerivedSeries {
    /// The source's identity when it is a DICOM series (same patient, study and frame of reference, its
    /// modality's storage class); nullopt: a new study, Secondary Capture.
    std::optional<fit::DicomIdentity> source;
    std::string description; // SeriesDescription, e.g. "MIP 10 mm / 5 mm axial"
    DerivedGeometry geometry;
    std::vector<DerivedImage> images; // in order along the slice normal (rowDirection x columnDirection)
    /// WindowCenter, WindowWidth for a viewer's first display; nullopt: none written.
    std::optional<std::array<double, 2>> window;
    /// [lo, hi] of the values the images can hold, which sets the series' one rescale (chooseRescale);
    /// nullopt: the finite values of `images`.
    std::optional<std::array<double, 2>> valueRange;
};

/// The stored value of a pixel without a value, also written as PixelPaddingValue.
inline constexpr std::int16_t PIXEL_PADDING = -32768;

/// How values become signed 16-bit stored values: value = stored * slope + intercept.
struct PixelRescale {
    double slope = 1.0;
    double intercept = 0.0;
};

/// The rescale for values in [lo, hi] (finite): slope 1, intercept 0 (whole units, as CT stores HU) when
/// they lie in [-32767, 32767] and span at least 1000 units, so rounding costs under 0.05 % of the span;
/// otherwise the span spread over [-32767, 32767]. -32768 stays free for PIXEL_PADDING.
PixelRescale chooseRescale(double lo, double hi);

/// The SOP class a derived image of this modality is stored as: CT Image Storage for "CT", MR Image
/// Storage for "MR", Secondary Capture Image Storage otherwise (and for a source that is not DICOM).
std::string storageClassFor(const std::optional<fit::DicomIdentity>& source);

/// Writes a series one image at a time, so that only the image being added is held: image k (in the
/// order added) goes to a temporary beside paths[k], and finish() renames them all once every image is
/// there. Destroyed without finish() (an error on the way), it leaves no file and no temporary. Throws
/// as writeDerivedSeries.
class DerivedSeriesWriter {
public:
    /// `series` gives everything but the images (its `images` are not read); its valueRange is required.
    DerivedSeriesWriter(DerivedSeries series, std::vector<std::string> paths);
    ~DerivedSeriesWriter();
    DerivedSeriesWriter(const DerivedSeriesWriter&) = delete;
    DerivedSeriesWriter& operator=(const DerivedSeriesWriter&) = delete;
    void add(const DerivedImage& image);
    /// Renames every file into place; throws std::invalid_argument unless one image per path was added.
    void finish();

private:
    struct State;
    std::unique_ptr<State> mState;
};

/// Writes image k of the series to paths[k] (one file per image, explicit VR little endian, GDCM), with a
/// new SeriesInstanceUID and SOPInstanceUIDs under GDCM's UID root. All or nothing: every file goes to
/// a temporary first and is renamed only once all are written, so a failure leaves none of them and no
/// temporary. Throws fit::InputError (e.g. "cannot write '<path>': ...") and std::invalid_argument for
/// a series that does not fit its paths or its own sizes.
void writeDerivedSeries(const DerivedSeries& series, const std::vector<std::string>& paths);

} // namespace vots::pacs
