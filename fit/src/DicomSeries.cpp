// Loads one DICOM series into a Volume: GDCM decodes each slice (any transfer syntax it supports) in a
// child process, the parent applies the rescale and stores the values in the layout's type.
#include "vots/fit/DicomSeries.h"

#include "DicomChild.h"
#include "DicomLayout.h"
#include "DicomSlice.h"
#include "InputFile.h"
#include "StoredSamples.h"

#include <algorithm>

namespace vots::fit {
namespace {

using detail::DicomSeriesLayout;
using detail::DicomSliceHeader;

/// Decodes slices [first, last] of the layout into `out`, plane first - first onwards; the other
/// slices' files are not opened again.
template <typename T>
void loadInto(const DicomSeriesLayout& layout, int first, int last, std::vector<T>& out) {
    const std::size_t pixels =
        static_cast<std::size_t>(layout.dims[0]) * static_cast<std::size_t>(layout.dims[1]);
    const auto begin = layout.slices.begin() + first;
    const auto end = layout.slices.begin() + last + 1;
    out.resize(pixels * static_cast<std::size_t>(last - first + 1));
    std::uint64_t largestFile = 0;
    for (auto slice = begin; slice != end; ++slice)
        largestFile = std::max(largestFile, slice->fileSize);
    // A multi-frame instance is decoded whole, every frame at once.
    const std::uint64_t decodedFile = pixels * static_cast<std::uint64_t>(begin->bitsAllocated / 8) *
                                      static_cast<std::uint64_t>(std::max(1, begin->frames));
    detail::runIsolated(
        [&](detail::ChildSender& child) {
            detail::DecodedFile decoded;
            for (auto slice = begin; slice != end; ++slice) {
                child.announce(slice->path);
                detail::decodeAndSend(*slice, layout.dims, child, decoded);
            }
        },
        [&](detail::ParentReceiver& parent) {
            std::vector<char> buffer;
            for (std::size_t z = 0; z < static_cast<std::size_t>(end - begin); ++z)
                detail::receiveSlice(*(begin + static_cast<std::ptrdiff_t>(z)), pixels, parent, buffer,
                                     out.data() + z * pixels);
        },
        detail::childLimitsHolding(std::max(largestFile, decodedFile)));
}

} // namespace

VolumeHeaderInfo dicomSeriesHeaderInfo(const std::string& folder, const std::string& seriesUid) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid);
    VolumeHeaderInfo info;
    for (int a = 0; a < 3; ++a)
        info.dims[a] = static_cast<std::uint64_t>(layout.dims[a]);
    info.sourceType = layout.valueType;
    info.frames = layout.frames;
    return info;
}

namespace {

/// Fills `into` (a grid of planes [first, last]) with those slices, in the storage asked for.
void loadSlices(const DicomSeriesLayout& layout, int first, int last, SampleStorage storage, Volume& into) {
    detail::withStoredSamples(into, layout.valueType, storage,
                              [&](auto& samples) { loadInto(layout, first, last, samples); });
}

} // namespace

ScalarType dicomSampleType(int bitsStored, bool pixelsSigned, double slope, double intercept) {
    DicomSliceHeader header;
    header.bitsStored = bitsStored;
    header.pixelsSigned = pixelsSigned;
    header.slope = slope;
    header.intercept = intercept;
    return detail::valueTypeOf({header});
}

Volume loadDicomSeries(const std::string& folder, const std::string& seriesUid, SampleStorage storage,
                       int frame) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid, frame);
    Volume volume = detail::gridOfLayout(layout, folder);
    loadSlices(layout, 0, layout.dims[2] - 1, storage, volume);
    return volume;
}

Volume loadDicomSeriesPlanes(const std::string& folder, int first, int last, Volume& grid,
                             const std::string& seriesUid, SampleStorage storage, int frame) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid, frame);
    grid = detail::gridOfLayout(layout, folder);
    Volume planes = detail::gridOfPlanes(grid, first, last); // throws for planes outside the series
    loadSlices(layout, first, last, storage, planes);
    return planes;
}

} // namespace vots::fit
