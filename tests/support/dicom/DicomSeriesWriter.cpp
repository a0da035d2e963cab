// Writes DICOM test series with GDCM's ImageWriter; compressed syntaxes through ImageChangeTransferSyntax.
#include "DicomSeriesWriter.h"
#include "DicomTextElement.h"

#include <gdcmAttribute.h>
#include <gdcmImageChangeTransferSyntax.h>
#include <gdcmImageWriter.h>
#include <gdcmTrace.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace vots::test {
namespace {

gdcm::TransferSyntax syntaxNamed(const std::string& name) {
    static const std::map<std::string, gdcm::TransferSyntax::TSType> SYNTAXES = {
        {"explicit", gdcm::TransferSyntax::ExplicitVRLittleEndian},
        {"implicit", gdcm::TransferSyntax::ImplicitVRLittleEndian},
        {"rle", gdcm::TransferSyntax::RLELossless},
        {"jpeg-lossless", gdcm::TransferSyntax::JPEGLosslessProcess14_1},
        {"jpeg-ls", gdcm::TransferSyntax::JPEGLSLossless},
        {"jpeg2000", gdcm::TransferSyntax::JPEG2000Lossless}};
    const auto it = SYNTAXES.find(name);
    if (it == SYNTAXES.end()) throw std::runtime_error("unknown transfer syntax '" + name + "'");
    return it->second;
}

void setText(gdcm::DataSet& data, std::uint16_t group, std::uint16_t element, gdcm::VR vr, std::string text) {
    data.Replace(textElement(group, element, vr, std::move(text)));
}

std::string decimal(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

std::vector<int> fileIndexOfSlice(int count, DicomFileOrder order) {
    std::vector<int> index(static_cast<std::size_t>(count));
    std::iota(index.begin(), index.end(), 0);
    if (order == DicomFileOrder::Descending) std::reverse(index.begin(), index.end());
    if (order == DicomFileOrder::Shuffled) std::shuffle(index.begin(), index.end(), std::mt19937(7));
    return index;
}

void writeSlice(const fit::Volume& volume, int z, int fileIndex, const std::string& path,
                const DicomWriteOptions& o) {
    const int columns = volume.dims[0] - (z == o.resizeSlice ? 1 : 0);
    const int rows = volume.dims[1];
    std::vector<char> pixels(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows) * 2);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < columns; ++x) {
            const double stored = std::round((volume.at(x, y, z) - o.intercept) / o.slope);
            const std::size_t at = 2 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(columns) +
                                        static_cast<std::size_t>(x));
            const auto bits = o.storeSigned ? static_cast<std::uint16_t>(static_cast<std::int16_t>(
                                                  std::clamp(stored, -32768.0, 32767.0)))
                                            : static_cast<std::uint16_t>(std::clamp(stored, 0.0, 65535.0));
            pixels[at] = static_cast<char>(bits & 0xff);
            pixels[at + 1] = static_cast<char>(bits >> 8);
        }

    const auto& r = o.orientation;
    const double normal[3] = {r[1] * r[5] - r[2] * r[4], r[2] * r[3] - r[0] * r[5],
                              r[0] * r[4] - r[1] * r[3]};
    double position[3];
    for (int a = 0; a < 3; ++a)
        position[a] = o.origin[a] + (o.slicesAlongNormal ? 1.0 : -1.0) * z * volume.spacing[2] * normal[a];

    // Heap-held: GDCM's writer and filters keep reference-counted pointers to the image they are given.
    gdcm::SmartPointer<gdcm::Image> held = new gdcm::Image;
    gdcm::Image& image = *held;
    image.SetNumberOfDimensions(2);
    image.SetDimension(0, static_cast<unsigned>(columns));
    image.SetDimension(1, static_cast<unsigned>(rows));
    gdcm::PixelFormat format(o.storeSigned ? gdcm::PixelFormat::INT16 : gdcm::PixelFormat::UINT16);
    format.SetBitsStored(static_cast<unsigned short>(o.bitsStored));
    format.SetHighBit(static_cast<unsigned short>(o.bitsStored - 1));
    image.SetPixelFormat(format);
    image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(o.syntax == "implicit" ? gdcm::TransferSyntax::ImplicitVRLittleEndian
                                                   : gdcm::TransferSyntax::ExplicitVRLittleEndian);
    image.SetSpacing(0, volume.spacing[0]); // GDCM's x: between columns
    image.SetSpacing(1, volume.spacing[1]);
    image.SetOrigin(position);
    image.SetOrigin(2, position[2]); // SetOrigin(const double*) copies only the two in-plane values
    image.SetDirectionCosines(o.orientation.data());
    image.SetSlope(o.slope);
    image.SetIntercept(o.intercept);
    gdcm::DataElement pixelData(gdcm::Tag(0x7fe0, 0x0010));
    pixelData.SetByteValue(pixels.data(), static_cast<std::uint32_t>(pixels.size()));
    image.SetDataElement(pixelData);

    gdcm::ImageWriter writer;
    if (o.syntax == "explicit" || o.syntax == "implicit") {
        writer.SetImage(image);
    } else {
        gdcm::ImageChangeTransferSyntax change;
        change.SetTransferSyntax(syntaxNamed(o.syntax));
        change.SetInput(image);
        if (!change.Change()) throw std::runtime_error("GDCM cannot encode " + o.syntax);
        writer.SetImage(change.GetOutput());
    }
    gdcm::DataSet& data = writer.GetFile().GetDataSet();
    setText(data, 0x0008, 0x0016, gdcm::VR::UI, "1.2.840.10008.5.1.4.1.1.2"); // CT Image Storage
    const std::string timePoint = o.temporalPosition > 0 ? std::to_string(o.temporalPosition) + "." : "";
    setText(data, 0x0008, 0x0018, gdcm::VR::UI,
            o.seriesUid + "." + timePoint + std::to_string(fileIndex + 1));
    if (o.temporalPosition > 0)
        setText(data, 0x0020, 0x0100, gdcm::VR::IS, std::to_string(o.temporalPosition));
    setText(data, 0x0008, 0x0060, gdcm::VR::CS, "CT");
    setText(data, 0x0008, 0x103e, gdcm::VR::LO, o.description);
    setText(data, 0x0010, 0x0010, gdcm::VR::PN, "Vots^Phantom");
    setText(data, 0x0010, 0x0020, gdcm::VR::LO, o.patientId);
    setText(data, 0x0020, 0x0052, gdcm::VR::UI, o.frameOfReferenceUid);
    setText(data, 0x0020, 0x000d, gdcm::VR::UI, o.seriesUid + ".0");
    setText(data, 0x0020, 0x000e, gdcm::VR::UI, o.seriesUid);
    setText(data, 0x0020, 0x0013, gdcm::VR::IS, std::to_string(fileIndex + 1));
    setText(data, 0x0018, 0x0050, gdcm::VR::DS, decimal(volume.spacing[2]));
    writer.SetFileName(path.c_str());
    if (!writer.Write()) throw std::runtime_error("GDCM cannot write " + path);

    if (z == o.truncateSlice) {
        const auto size = std::filesystem::file_size(path);
        std::filesystem::resize_file(path, size - pixels.size() / 2);
    }
}

} // namespace

void writeDicomSeries(const fit::Volume& volume, const std::string& folder,
                      const DicomWriteOptions& options) {
    gdcm::Trace::SetWarning(false);
    std::filesystem::create_directories(folder);
    const std::vector<int> fileIndex = fileIndexOfSlice(volume.dims[2], options.order);
    for (int z = 0; z < volume.dims[2]; ++z) {
        if (z == options.dropSlice) continue;
        char name[64];
        std::snprintf(name, sizeof name, "-%04d.dcm", fileIndex[static_cast<std::size_t>(z)] + 1);
        const std::string path = (std::filesystem::path(folder) / (options.filePrefix + name)).string();
        writeSlice(volume, z, fileIndex[static_cast<std::size_t>(z)], path, options);
    }
    if (options.junkFile) {
        std::FILE* file = std::fopen((std::filesystem::path(folder) / "README.txt").c_str(), "w");
        if (file == nullptr) throw std::runtime_error("cannot write README.txt in " + folder);
        std::fputs("Not a DICOM file: the reader skips it.\n", file);
        std::fclose(file);
    }
}

} // namespace vots::test
