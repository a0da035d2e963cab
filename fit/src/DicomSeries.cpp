// Loads one DICOM series into a Volume: GDCM decodes each slice (any transfer syntax it supports) in a
// child process, the parent applies the rescale and stores the values in the layout's type.
#include "vots/fit/DicomSeries.h"

#include "DicomChild.h"
#include "DicomLayout.h"
#include "InputFile.h"
#include "StoredSamples.h"

#include <gdcmImage.h>
#include <gdcmImageReader.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace vots::fit {
namespace {

using detail::DicomSeriesLayout;
using detail::DicomSliceHeader;
using detail::throwInputError;

/// The folder's own name, also for "dir/" and ".".
std::string folderName(const std::string& folder) {
    std::filesystem::path path = std::filesystem::path(folder).lexically_normal();
    if (path.filename().empty()) path = path.parent_path();
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    return ec ? path.filename().string() : absolute.lexically_normal().filename().string();
}

/// How the child's decoded pixels are laid out, sent before each slice's bytes.
struct SliceFormat {
    int bitsAllocated = 16;
    int bitsStored = 16;
    int highBit = 15;
    int pixelsSigned = 0;
};

/// One stored pixel as an integer: masked to BitsStored and sign-extended when the pixels are signed, so
/// bits above HighBit (overlays, garbage) never change a value.
struct PixelDecoder {
    int bytes = 2;
    int shift = 0;
    std::uint32_t mask = 0xffff;
    std::uint32_t signBit = 0;

    explicit PixelDecoder(const SliceFormat& format) {
        bytes = format.bitsAllocated / 8;
        const int stored = std::clamp(format.bitsStored, 1, format.bitsAllocated);
        shift = std::clamp(format.highBit + 1 - stored, 0, format.bitsAllocated - stored);
        mask = stored >= 32 ? 0xffffffffu : (1u << stored) - 1u;
        signBit = format.pixelsSigned != 0 ? 1u << (stored - 1) : 0u;
    }
    long long at(const char* buffer, std::size_t index) const {
        std::uint32_t raw = 0;
        if (bytes == 1) raw = static_cast<unsigned char>(buffer[index]);
        if (bytes == 2) {
            std::uint16_t v;
            std::memcpy(&v, buffer + 2 * index, 2);
            raw = v;
        }
        if (bytes == 4) std::memcpy(&raw, buffer + 4 * index, 4);
        raw = (raw >> shift) & mask;
        if (signBit != 0 && (raw & signBit) != 0)
            return static_cast<long long>(raw) - 2 * static_cast<long long>(signBit);
        return static_cast<long long>(raw);
    }
};

/// In the child: decodes one slice with GDCM and sends its format, then exactly its pixel bytes.
void decodeAndSend(const DicomSliceHeader& slice, const std::array<int, 3>& dims,
                   detail::ChildSender& child) {
    gdcm::ImageReader reader;
    reader.SetFileName(slice.path.c_str());
    if (!reader.Read()) throwInputError(slice.path, "cannot be read (truncated or damaged DICOM file)");
    const gdcm::Image& image = reader.GetImage();
    const gdcm::PixelFormat format = image.GetPixelFormat();
    if (image.GetDimension(0) != static_cast<unsigned>(dims[0]) ||
        image.GetDimension(1) != static_cast<unsigned>(dims[1]))
        throwInputError(slice.path, "its pixel data is not the size its header announces");
    if (format.GetSamplesPerPixel() != 1 ||
        (format.GetBitsAllocated() != 8 && format.GetBitsAllocated() != 16 &&
         format.GetBitsAllocated() != 32))
        throwInputError(slice.path,
                        "unsupported pixel format " + std::string(format.GetScalarTypeAsString()));
    const std::size_t pixels = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]);
    const std::size_t expected = pixels * (format.GetBitsAllocated() / 8u);
    if (image.GetBufferLength() < expected)
        throwInputError(slice.path, "its pixel data is shorter than " + std::to_string(dims[0]) + "x" +
                                        std::to_string(dims[1]) + " pixels (truncated file?)");
    std::vector<char> buffer(image.GetBufferLength());
    if (!image.GetBuffer(buffer.data()))
        throwInputError(slice.path, "its pixel data cannot be decoded (truncated file, or transfer syntax " +
                                        std::string(image.GetTransferSyntax().GetString()) +
                                        " that GDCM cannot decode)");
    const SliceFormat sent{format.GetBitsAllocated(), format.GetBitsStored(), format.GetHighBit(),
                           format.GetPixelRepresentation() == 1 ? 1 : 0};
    child.send(&sent, sizeof sent);
    child.send(buffer.data(), expected);
}

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
    const std::uint64_t decodedSlice = pixels * static_cast<std::uint64_t>(begin->bitsAllocated / 8);
    detail::runIsolated(
        [&](detail::ChildSender& child) {
            for (auto slice = begin; slice != end; ++slice) {
                child.announce(slice->path);
                decodeAndSend(*slice, layout.dims, child);
            }
        },
        [&](detail::ParentReceiver& parent) {
            std::vector<char> buffer;
            for (std::size_t z = 0; z < static_cast<std::size_t>(end - begin); ++z) {
                const DicomSliceHeader& header = *(begin + static_cast<std::ptrdiff_t>(z));
                SliceFormat format;
                parent.nextInto(reinterpret_cast<char*>(&format), sizeof format);
                buffer.resize(pixels * static_cast<std::size_t>(format.bitsAllocated / 8));
                parent.nextInto(buffer.data(), buffer.size());
                const PixelDecoder decoder(format);
                T* slice = out.data() + z * pixels;
                for (std::size_t i = 0; i < pixels; ++i) {
                    const double value =
                        header.slope * static_cast<double>(decoder.at(buffer.data(), i)) + header.intercept;
                    if constexpr (std::is_integral_v<T>) {
                        // The type was chosen from BitsStored; pixel data beyond it contradicts the header.
                        if (value < static_cast<double>(std::numeric_limits<T>::lowest()) ||
                            value > static_cast<double>(std::numeric_limits<T>::max()))
                            throwInputError(header.path,
                                            "a pixel value is outside the range its BitsStored announces");
                    }
                    slice[i] = static_cast<T>(value);
                }
            }
        },
        detail::childLimitsHolding(std::max(largestFile, decodedSlice)));
}

} // namespace

VolumeHeaderInfo dicomSeriesHeaderInfo(const std::string& folder, const std::string& seriesUid) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid);
    VolumeHeaderInfo info;
    for (int a = 0; a < 3; ++a)
        info.dims[a] = static_cast<std::uint64_t>(layout.dims[a]);
    info.sourceType = layout.valueType;
    return info;
}

namespace {

/// The series' grid as loadDicomSeries gives it, without samples.
Volume gridOfLayout(const DicomSeriesLayout& layout, const std::string& folder) {
    Volume volume;
    volume.dims = layout.dims;
    volume.spacing = layout.spacing;
    volume.origin = layout.origin;
    volume.patientAxes = layout.patientAxes;
    volume.orientationKnown = true;
    volume.sourceType = layout.valueType;
    volume.name = folderName(folder);
    return volume;
}

/// Fills `into` (a grid of planes [first, last]) with those slices, in the storage asked for.
void loadSlices(const DicomSeriesLayout& layout, int first, int last, SampleStorage storage, Volume& into) {
    const bool compact = storage == SampleStorage::Source && layout.valueType != ScalarType::Float32;
    if (!compact) {
        loadInto(layout, first, last, into.values);
    } else if (layout.valueType == ScalarType::UInt8) {
        loadInto(layout, first, last, into.compact.emplace<std::vector<std::uint8_t>>());
    } else if (layout.valueType == ScalarType::Int16) {
        loadInto(layout, first, last, into.compact.emplace<std::vector<std::int16_t>>());
    } else {
        loadInto(layout, first, last, into.compact.emplace<std::vector<std::uint16_t>>());
    }
}

} // namespace

Volume loadDicomSeries(const std::string& folder, const std::string& seriesUid, SampleStorage storage) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid);
    Volume volume = gridOfLayout(layout, folder);
    loadSlices(layout, 0, layout.dims[2] - 1, storage, volume);
    return volume;
}

Volume loadDicomSeriesPlanes(const std::string& folder, int first, int last, Volume& grid,
                             const std::string& seriesUid, SampleStorage storage) {
    const DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid);
    grid = gridOfLayout(layout, folder);
    Volume planes = detail::gridOfPlanes(grid, first, last); // throws for planes outside the series
    loadSlices(layout, first, last, storage, planes);
    return planes;
}

} // namespace vots::fit
