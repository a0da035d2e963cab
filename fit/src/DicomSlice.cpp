// One slice's pixels decoded by GDCM, in the DICOM reader's child process.
#include "DicomSlice.h"

#include <gdcmImage.h>
#include <gdcmImageReader.h>

namespace vots::fit::detail {
namespace {

/// Decodes every frame of `slice`'s file into `into`, checking the image against the header's grid.
void decodeFile(const DicomSliceHeader& slice, const std::array<int, 3>& dims, DecodedFile& into) {
    into.path.clear();
    gdcm::ImageReader reader;
    reader.SetFileName(slice.path.c_str());
    if (!reader.Read()) throwInputError(slice.path, "cannot be read (truncated or damaged DICOM file)");
    const gdcm::Image& image = reader.GetImage();
    const gdcm::PixelFormat format = image.GetPixelFormat();
    const unsigned frames = image.GetNumberOfDimensions() > 2 ? image.GetDimension(2) : 1u;
    if (image.GetDimension(0) != static_cast<unsigned>(dims[0]) ||
        image.GetDimension(1) != static_cast<unsigned>(dims[1]) ||
        frames != static_cast<unsigned>(std::max(1, slice.frames)))
        throwInputError(slice.path, "its pixel data is not the size its header announces");
    if (format.GetSamplesPerPixel() != 1 ||
        (format.GetBitsAllocated() != 8 && format.GetBitsAllocated() != 16 &&
         format.GetBitsAllocated() != 32))
        throwInputError(slice.path,
                        "unsupported pixel format " + std::string(format.GetScalarTypeAsString()));
    const std::size_t expected = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
                                 (format.GetBitsAllocated() / 8u) * frames;
    if (image.GetBufferLength() < expected)
        throwInputError(slice.path, "its pixel data is shorter than " + std::to_string(frames) +
                                        " frames of " + std::to_string(dims[0]) + "x" +
                                        std::to_string(dims[1]) + " pixels (truncated file?)");
    into.pixels.resize(image.GetBufferLength());
    if (!image.GetBuffer(into.pixels.data()))
        throwInputError(slice.path, "its pixel data cannot be decoded (truncated file, or transfer syntax " +
                                        std::string(image.GetTransferSyntax().GetString()) +
                                        " that GDCM cannot decode)");
    into.format = {format.GetBitsAllocated(), format.GetBitsStored(), format.GetHighBit(),
                   format.GetPixelRepresentation() == 1 ? 1 : 0};
    into.path = slice.path;
}

} // namespace

void decodeAndSend(const DicomSliceHeader& slice, const std::array<int, 3>& dims, ChildSender& child,
                   DecodedFile& last) {
    if (last.path != slice.path) decodeFile(slice, dims, last);
    const std::size_t frameBytes = static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
                                   static_cast<std::size_t>(last.format.bitsAllocated / 8);
    child.send(&last.format, sizeof last.format);
    child.send(last.pixels.data() + static_cast<std::size_t>(slice.frameIndex) * frameBytes, frameBytes);
}

} // namespace vots::fit::detail
