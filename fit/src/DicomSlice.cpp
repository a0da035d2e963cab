// One slice's pixels decoded by GDCM, in the DICOM reader's child process.
#include "DicomSlice.h"

#include <gdcmImage.h>
#include <gdcmImageReader.h>

namespace vots::fit::detail {

void decodeAndSend(const DicomSliceHeader& slice, const std::array<int, 3>& dims, ChildSender& child) {
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

} // namespace vots::fit::detail
