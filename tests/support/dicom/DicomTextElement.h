// Test-data writers' text element: DICOM's padding to even length, for the series and multi-frame writers.
#pragma once

#include <gdcmDataElement.h>
#include <gdcmVR.h>

#include <cstdint>
#include <string>

namespace vots::test {

/// A text element, padded to even length as DICOM requires (UIDs with NUL, others with a space).
inline gdcm::DataElement textElement(std::uint16_t group, std::uint16_t element, gdcm::VR vr,
                                     std::string text) {
    if (text.size() % 2 == 1) text += vr == gdcm::VR::UI ? '\0' : ' ';
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(vr);
    de.SetByteValue(text.data(), static_cast<std::uint32_t>(text.size()));
    return de;
}

} // namespace vots::test
