// One image of a derived series as a DICOM file: the patient, study, series, frame of reference, equipment,
// image plane and pixel modules, written element by element with GDCM.
#include "DerivedSeriesFile.h"

#include <gdcmAttribute.h>
#include <gdcmDataSet.h>
#include <gdcmFile.h>
#include <gdcmWriter.h>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace vots::pacs::detail {
namespace {

/// A text element, padded to even length as DICOM requires (UIDs with NUL, others with a space). Empty
/// text writes the element empty: a type 2 element present without a value.
void setText(gdcm::DataSet& data, std::uint16_t group, std::uint16_t element, gdcm::VR vr, std::string text) {
    if (text.size() % 2 == 1) text += vr == gdcm::VR::UI ? '\0' : ' ';
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(vr);
    de.SetByteValue(text.data(), static_cast<std::uint32_t>(text.size()));
    data.Replace(de);
}

/// A decimal string value: at most 16 characters, as DS allows.
std::string decimal(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", std::abs(value) < 1e-9 ? 0.0 : value);
    return text;
}

std::string decimals(const double* values, int count) {
    std::string text;
    for (int i = 0; i < count; ++i)
        text += (i > 0 ? "\\" : "") + decimal(values[i]);
    return text;
}

void setUnsigned(gdcm::DataSet& data, std::uint16_t group, std::uint16_t element, std::uint16_t value) {
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::US);
    de.SetByteValue(reinterpret_cast<const char*>(&value), 2); // little endian on the hosts we build for
    data.Replace(de);
}

void setSigned(gdcm::DataSet& data, std::uint16_t group, std::uint16_t element, std::int16_t value) {
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::SS);
    de.SetByteValue(reinterpret_cast<const char*>(&value), 2);
    data.Replace(de);
}

std::string modeOf(const std::optional<fit::DicomIdentity>& source) {
    if (source && (source->modality == "CT" || source->modality == "MR")) return source->modality;
    return "OT";
}

void addPatientAndStudy(gdcm::DataSet& data, const DerivedSeries& series, const SeriesStamp& stamp) {
    const fit::DicomIdentity identity = series.source.value_or(fit::DicomIdentity{});
    setText(data, 0x0010, 0x0010, gdcm::VR::PN, identity.patientName);
    setText(data, 0x0010, 0x0020, gdcm::VR::LO, identity.patientId);
    setText(data, 0x0010, 0x0030, gdcm::VR::DA, identity.patientBirthDate);
    setText(data, 0x0010, 0x0040, gdcm::VR::CS, identity.patientSex);
    setText(data, 0x0020, 0x000d, gdcm::VR::UI, stamp.studyInstanceUid);
    setText(data, 0x0020, 0x0010, gdcm::VR::SH, identity.studyId);
    setText(data, 0x0008, 0x0020, gdcm::VR::DA, series.source ? identity.studyDate : stamp.date);
    setText(data, 0x0008, 0x0030, gdcm::VR::TM, series.source ? identity.studyTime : stamp.time);
    setText(data, 0x0008, 0x0050, gdcm::VR::SH, identity.accessionNumber);
    setText(data, 0x0008, 0x0090, gdcm::VR::PN, identity.referringPhysicianName);
    if (!identity.studyDescription.empty())
        setText(data, 0x0008, 0x1030, gdcm::VR::LO, identity.studyDescription);
    setText(data, 0x0008, 0x0070, gdcm::VR::LO, identity.manufacturer);
}

void addSeriesAndImage(gdcm::DataSet& data, const DerivedSeries& series, int index, const SeriesStamp& stamp,
                       const std::string& sopUid) {
    const std::string modality = modeOf(series.source);
    setText(data, 0x0008, 0x0016, gdcm::VR::UI, storageClassFor(series.source));
    setText(data, 0x0008, 0x0018, gdcm::VR::UI, sopUid);
    setText(data, 0x0008, 0x0008, gdcm::VR::CS, "DERIVED\\SECONDARY");
    setText(data, 0x0008, 0x0060, gdcm::VR::CS, modality);
    setText(data, 0x0008, 0x0021, gdcm::VR::DA, stamp.date);
    setText(data, 0x0008, 0x0031, gdcm::VR::TM, stamp.time);
    setText(data, 0x0008, 0x0023, gdcm::VR::DA, stamp.date);
    setText(data, 0x0008, 0x0033, gdcm::VR::TM, stamp.time);
    setText(data, 0x0008, 0x103e, gdcm::VR::LO, series.description.substr(0, 64));
    setText(data, 0x0008, 0x2111, gdcm::VR::ST, series.description);
    setText(data, 0x0020, 0x000e, gdcm::VR::UI, stamp.seriesInstanceUid);
    setText(data, 0x0020, 0x0011, gdcm::VR::IS, "");
    setText(data, 0x0020, 0x0012, gdcm::VR::IS, "");
    setText(data, 0x0020, 0x0013, gdcm::VR::IS, std::to_string(index + 1));
    setText(data, 0x0020, 0x0052, gdcm::VR::UI, stamp.frameOfReferenceUid);
    setText(data, 0x0020, 0x1040, gdcm::VR::LO, "");
    // What each modality's image module asks for, where a derived image has no measured value.
    if (modality == "CT") setText(data, 0x0018, 0x0060, gdcm::VR::DS, "");
    if (modality == "MR") {
        setText(data, 0x0018, 0x0020, gdcm::VR::CS, "RM"); // research mode: no acquisition sequence
        setText(data, 0x0018, 0x0021, gdcm::VR::CS, "NONE");
        setText(data, 0x0018, 0x0022, gdcm::VR::CS, ""); // ScanOptions
        setText(data, 0x0018, 0x0023, gdcm::VR::CS, ""); // MRAcquisitionType
        setText(data, 0x0018, 0x0081, gdcm::VR::DS, ""); // EchoTime
        setText(data, 0x0018, 0x0091, gdcm::VR::IS, ""); // EchoTrainLength
    }
    if (modality == "OT") setText(data, 0x0008, 0x0064, gdcm::VR::CS, "WSD"); // workstation
}

void addPlane(gdcm::DataSet& data, const DerivedSeries& series, const DerivedImage& image) {
    const DerivedGeometry& g = series.geometry;
    const double orientation[6] = {g.rowDirection[0],    g.rowDirection[1],    g.rowDirection[2],
                                   g.columnDirection[0], g.columnDirection[1], g.columnDirection[2]};
    const double spacing[2] = {g.pixelSpacingMm, g.pixelSpacingMm};
    const std::array<double, 3> normal{
        g.rowDirection[1] * g.columnDirection[2] - g.rowDirection[2] * g.columnDirection[1],
        g.rowDirection[2] * g.columnDirection[0] - g.rowDirection[0] * g.columnDirection[2],
        g.rowDirection[0] * g.columnDirection[1] - g.rowDirection[1] * g.columnDirection[0]};
    double location = 0.0;
    for (int a = 0; a < 3; ++a)
        location += normal[a] * image.firstPixelCentre[a];
    setText(data, 0x0020, 0x0032, gdcm::VR::DS, decimals(image.firstPixelCentre.data(), 3));
    setText(data, 0x0020, 0x0037, gdcm::VR::DS, decimals(orientation, 6));
    setText(data, 0x0020, 0x1041, gdcm::VR::DS, decimal(location));
    setText(data, 0x0028, 0x0030, gdcm::VR::DS, decimals(spacing, 2));
    setText(data, 0x0018, 0x0050, gdcm::VR::DS, decimal(g.sliceThicknessMm));
    setText(data, 0x0018, 0x0088, gdcm::VR::DS, decimal(g.spacingBetweenSlicesMm));
}

void addPixels(gdcm::DataSet& data, const DerivedSeries& series, const DerivedImage& image,
               const SeriesStamp& stamp) {
    setUnsigned(data, 0x0028, 0x0002, 1);
    setText(data, 0x0028, 0x0004, gdcm::VR::CS, "MONOCHROME2");
    setUnsigned(data, 0x0028, 0x0010, static_cast<std::uint16_t>(image.height));
    setUnsigned(data, 0x0028, 0x0011, static_cast<std::uint16_t>(image.width));
    setUnsigned(data, 0x0028, 0x0100, 16);
    setUnsigned(data, 0x0028, 0x0101, 16);
    setUnsigned(data, 0x0028, 0x0102, 15);
    setUnsigned(data, 0x0028, 0x0103, 1); // signed
    setSigned(data, 0x0028, 0x0120, PIXEL_PADDING);
    setText(data, 0x0028, 0x1052, gdcm::VR::DS, decimal(stamp.rescale.intercept));
    setText(data, 0x0028, 0x1053, gdcm::VR::DS, decimal(stamp.rescale.slope));
    setText(data, 0x0028, 0x1054, gdcm::VR::LO, modeOf(series.source) == "CT" ? "HU" : "US");
    if (series.window) {
        setText(data, 0x0028, 0x1050, gdcm::VR::DS, decimal((*series.window)[0]));
        setText(data, 0x0028, 0x1051, gdcm::VR::DS, decimal((*series.window)[1]));
    }
    std::vector<std::int16_t> stored(image.pixels.size());
    for (std::size_t i = 0; i < stored.size(); ++i)
        stored[i] = storedValue(image.pixels[i], stamp.rescale);
    gdcm::DataElement pixels(gdcm::Tag(0x7fe0, 0x0010));
    pixels.SetVR(gdcm::VR::OW);
    pixels.SetByteValue(reinterpret_cast<const char*>(stored.data()),
                        static_cast<std::uint32_t>(stored.size() * sizeof(std::int16_t)));
    data.Replace(pixels);
}

} // namespace

std::vector<std::uint8_t> encodeDerivedImage(const DerivedSeries& series, const DerivedImage& image,
                                             int index, const SeriesStamp& stamp, const std::string& sopUid) {
    gdcm::Writer writer;
    gdcm::File& file = writer.GetFile();
    file.GetHeader().SetDataSetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
    gdcm::DataSet& data = file.GetDataSet();
    addPatientAndStudy(data, series, stamp);
    addSeriesAndImage(data, series, index, stamp, sopUid);
    addPlane(data, series, image);
    addPixels(data, series, image, stamp);
    std::ostringstream bytes;
    writer.SetStream(bytes);
    if (!writer.Write()) throw std::runtime_error("GDCM cannot encode image " + std::to_string(index + 1));
    const std::string text = bytes.str();
    return {text.begin(), text.end()};
}

} // namespace vots::pacs::detail
