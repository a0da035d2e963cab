// Writes a multi-frame DICOM instance: GDCM's ImageWriter for the pixels, then its file rewritten with the
// functional groups of an Enhanced CT in place of the top-level position, spacing and rescale.
#include "DicomMultiFrameWriter.h"
#include "DicomTextElement.h"

#include <gdcmImageChangeTransferSyntax.h>
#include <gdcmImageWriter.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmTrace.h>
#include <gdcmWriter.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace vots::test {
namespace {

const char* const ENHANCED_CT = "1.2.840.10008.5.1.4.1.1.2.1"; // SOP class UID

std::string decimals(std::initializer_list<double> values) {
    std::string text;
    for (const double v : values) {
        char part[32];
        std::snprintf(part, sizeof part, "%.6g", v);
        text += (text.empty() ? "" : "\\") + std::string(part);
    }
    return text;
}

/// A sequence element of one item per data set.
gdcm::DataElement sequenceOf(const gdcm::Tag& tag, const std::vector<gdcm::DataSet>& items) {
    gdcm::SmartPointer<gdcm::SequenceOfItems> sequence = new gdcm::SequenceOfItems;
    sequence->SetLengthToUndefined();
    for (const gdcm::DataSet& data : items) {
        gdcm::Item item;
        item.SetVLToUndefined();
        item.SetNestedDataSet(data);
        sequence->AddItem(item);
    }
    gdcm::DataElement de(tag);
    de.SetVR(gdcm::VR::SQ);
    de.SetValue(*sequence);
    de.SetVLToUndefined();
    return de;
}

/// A functional-group macro: the sequence `tag` of one item holding `elements`.
gdcm::DataElement macro(const gdcm::Tag& tag, const std::vector<gdcm::DataElement>& elements) {
    gdcm::DataSet data;
    for (const gdcm::DataElement& de : elements)
        data.Insert(de);
    return sequenceOf(tag, {data});
}

gdcm::DataElement unsignedLong(std::uint16_t group, std::uint16_t element, std::uint32_t value) {
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::UL);
    de.SetByteValue(reinterpret_cast<const char*>(&value), 4); // little endian on the test machines
    return de;
}

} // namespace

void writeMultiFrameDicom(const std::vector<fit::Volume>& timePoints, const std::string& path,
                          const MultiFrameOptions& o) {
    gdcm::Trace::SetWarning(false);
    const fit::Volume& first = timePoints.at(0);
    const int columns = first.dims[0], rows = first.dims[1], slices = first.dims[2];
    const int frames = slices * static_cast<int>(timePoints.size());
    const std::size_t plane = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    std::vector<std::int16_t> stored(plane * static_cast<std::size_t>(frames));
    const auto sliceOfFrame = [&](int f) {
        return o.slicesDescending ? slices - 1 - f % slices : f % slices;
    };
    for (int f = 0; f < frames; ++f)
        for (int y = 0; y < rows; ++y)
            for (int x = 0; x < columns; ++x)
                stored[static_cast<std::size_t>(f) * plane + static_cast<std::size_t>(y * columns + x)] =
                    static_cast<std::int16_t>(std::lround(
                        timePoints[static_cast<std::size_t>(f / slices)].at(x, y, sliceOfFrame(f)) -
                        o.intercept));

    gdcm::SmartPointer<gdcm::Image> held = new gdcm::Image;
    gdcm::Image& image = *held;
    image.SetNumberOfDimensions(3);
    image.SetDimension(0, static_cast<unsigned>(columns));
    image.SetDimension(1, static_cast<unsigned>(rows));
    image.SetDimension(2, static_cast<unsigned>(frames));
    image.SetPixelFormat(gdcm::PixelFormat(gdcm::PixelFormat::INT16));
    image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
    gdcm::DataElement pixelData(gdcm::Tag(0x7fe0, 0x0010));
    pixelData.SetByteValue(reinterpret_cast<const char*>(stored.data()),
                           static_cast<std::uint32_t>(stored.size() * sizeof(std::int16_t)));
    image.SetDataElement(pixelData);
    gdcm::ImageWriter writer;
    gdcm::ImageChangeTransferSyntax change;
    if (o.syntax == "rle") {
        change.SetTransferSyntax(gdcm::TransferSyntax::RLELossless);
        change.SetInput(image);
        if (!change.Change()) throw std::runtime_error("GDCM cannot encode RLE");
        writer.SetImage(change.GetOutput());
    } else {
        writer.SetImage(image);
    }
    // GDCM writes a 3D image only for a multi-frame storage class.
    writer.GetFile().GetDataSet().Replace(textElement(0x0008, 0x0016, gdcm::VR::UI, ENHANCED_CT));
    writer.SetFileName(path.c_str());
    if (!writer.Write()) throw std::runtime_error("GDCM cannot write " + path);

    // The written file, given the tags of an Enhanced CT (or a plain stack) in place of what GDCM chose
    // (its own functional groups too, which place the frames at its image's origin and spacing).
    gdcm::Reader reader;
    reader.SetFileName(path.c_str());
    if (!reader.Read()) throw std::runtime_error("GDCM cannot read back " + path);
    gdcm::DataSet& data = reader.GetFile().GetDataSet();
    for (const auto& [group, element] :
         {std::pair{0x0020, 0x0032}, std::pair{0x0020, 0x0037}, std::pair{0x0028, 0x0030},
          std::pair{0x0028, 0x1052}, std::pair{0x0028, 0x1053}, std::pair{0x0018, 0x0088},
          std::pair{0x0028, 0x1054}, std::pair{0x0018, 0x0050}, std::pair{0x5200, 0x9229},
          std::pair{0x5200, 0x9230}})
        data.Remove(gdcm::Tag(static_cast<std::uint16_t>(group), static_cast<std::uint16_t>(element)));
    data.Replace(textElement(0x0008, 0x0016, gdcm::VR::UI, ENHANCED_CT));
    data.Replace(textElement(0x0008, 0x0018, gdcm::VR::UI, o.seriesUid + ".1"));
    data.Replace(textElement(0x0008, 0x0060, gdcm::VR::CS, "CT"));
    data.Replace(textElement(0x0020, 0x000d, gdcm::VR::UI, o.seriesUid + ".0"));
    data.Replace(textElement(0x0020, 0x000e, gdcm::VR::UI, o.seriesUid));
    data.Replace(textElement(0x0020, 0x0013, gdcm::VR::IS, "1"));
    data.Replace(textElement(0x0028, 0x0008, gdcm::VR::IS,
                             std::to_string(o.announcedFrames > 0 ? o.announcedFrames : frames)));
    const std::string orientation = decimals({1, 0, 0, 0, 1, 0});
    const std::string spacing = decimals({first.spacing[1], first.spacing[0]});
    const auto positionOf = [&](int slice) {
        return decimals({o.origin[0], o.origin[1], o.origin[2] + slice * first.spacing[2]});
    };
    if (!o.functionalGroups) {
        data.Replace(textElement(0x0020, 0x0032, gdcm::VR::DS, positionOf(0)));
        data.Replace(textElement(0x0020, 0x0037, gdcm::VR::DS, orientation));
        data.Replace(textElement(0x0028, 0x0030, gdcm::VR::DS, spacing));
        data.Replace(textElement(0x0018, 0x0088, gdcm::VR::DS, decimals({first.spacing[2]})));
        data.Replace(textElement(0x0028, 0x1052, gdcm::VR::DS, decimals({o.intercept})));
        data.Replace(textElement(0x0028, 0x1053, gdcm::VR::DS, "1"));
    } else {
        gdcm::DataSet shared;
        shared.Insert(
            macro(gdcm::Tag(0x0020, 0x9116), {textElement(0x0020, 0x0037, gdcm::VR::DS, orientation)}));
        shared.Insert(macro(gdcm::Tag(0x0028, 0x9110),
                            {textElement(0x0028, 0x0030, gdcm::VR::DS, spacing),
                             textElement(0x0018, 0x0050, gdcm::VR::DS, decimals({first.spacing[2]}))}));
        shared.Insert(macro(gdcm::Tag(0x0028, 0x9145),
                            {textElement(0x0028, 0x1052, gdcm::VR::DS, decimals({o.intercept})),
                             textElement(0x0028, 0x1053, gdcm::VR::DS, "1"),
                             textElement(0x0028, 0x1054, gdcm::VR::LO, "HU")}));
        data.Replace(sequenceOf(gdcm::Tag(0x5200, 0x9229), {shared}));
        std::vector<gdcm::DataSet> perFrame(static_cast<std::size_t>(frames));
        for (int f = 0; f < frames; ++f) {
            gdcm::DataSet& item = perFrame[static_cast<std::size_t>(f)];
            item.Insert(macro(gdcm::Tag(0x0020, 0x9113),
                              {textElement(0x0020, 0x0032, gdcm::VR::DS, positionOf(sliceOfFrame(f)))}));
            if (timePoints.size() > 1)
                item.Insert(
                    macro(gdcm::Tag(0x0020, 0x9111),
                          {unsignedLong(0x0020, 0x9128, static_cast<std::uint32_t>(f / slices + 1))}));
        }
        data.Replace(sequenceOf(gdcm::Tag(0x5200, 0x9230), perFrame));
    }
    gdcm::Writer rewrite;
    rewrite.SetFile(reader.GetFile());
    rewrite.SetFileName(path.c_str());
    if (!rewrite.Write()) throw std::runtime_error("GDCM cannot rewrite " + path);
}

} // namespace vots::test
