// Reads the patient, study and frame of reference a DICOM series belongs to, for the series derived from it.
#include "vots/fit/DicomSeries.h"

#include "DicomChild.h"
#include "DicomLayout.h"
#include "InputFile.h"

#include <gdcmReader.h>
#include <gdcmStringFilter.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace vots::fit {
namespace {

struct IdentityTag {
    std::uint16_t group;
    std::uint16_t element;
    std::string DicomIdentity::*field;
};

const std::vector<IdentityTag>& identityTags() {
    static const std::vector<IdentityTag> TAGS = {
        {0x0010, 0x0020, &DicomIdentity::patientId},
        {0x0010, 0x0010, &DicomIdentity::patientName},
        {0x0010, 0x0030, &DicomIdentity::patientBirthDate},
        {0x0010, 0x0040, &DicomIdentity::patientSex},
        {0x0020, 0x000d, &DicomIdentity::studyInstanceUid},
        {0x0020, 0x0010, &DicomIdentity::studyId},
        {0x0008, 0x0020, &DicomIdentity::studyDate},
        {0x0008, 0x0030, &DicomIdentity::studyTime},
        {0x0008, 0x0050, &DicomIdentity::accessionNumber},
        {0x0008, 0x0090, &DicomIdentity::referringPhysicianName},
        {0x0008, 0x1030, &DicomIdentity::studyDescription},
        {0x0008, 0x0060, &DicomIdentity::modality},
        {0x0020, 0x0052, &DicomIdentity::frameOfReferenceUid},
        {0x0008, 0x0070, &DicomIdentity::manufacturer},
    };
    return TAGS;
}

std::string trimmed(std::string text) {
    text.erase(std::find(text.begin(), text.end(), '\0'), text.end()); // the padding of UIDs
    const auto first = text.find_first_not_of(' ');
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

/// In the child: every identity tag of the file's header, in identityTags() order.
void sendIdentity(const std::string& path, detail::ChildSender& child) {
    child.announce(path);
    const gdcm::Tag pixelData(0x7fe0, 0x0010);
    gdcm::Reader reader;
    reader.SetFileName(path.c_str());
    if (!reader.ReadUpToTag(pixelData, {pixelData}))
        detail::throwInputError(path, "is a DICOM file that cannot be read (truncated or damaged header)");
    const gdcm::DataSet& data = reader.GetFile().GetDataSet();
    gdcm::StringFilter filter;
    filter.SetFile(reader.GetFile());
    for (const IdentityTag& t : identityTags()) {
        const gdcm::Tag tag(t.group, t.element);
        const bool present = data.FindDataElement(tag) && !data.GetDataElement(tag).IsEmpty();
        child.send(present ? trimmed(filter.ToString(tag)) : std::string());
    }
}

} // namespace

DicomIdentity readDicomIdentity(const std::string& folder, const std::string& seriesUid) {
    const detail::DicomSeriesLayout layout = detail::layoutDicomSeries(folder, seriesUid);
    const std::string path = layout.slices.front().path;
    DicomIdentity identity;
    detail::runIsolated([&](detail::ChildSender& child) { sendIdentity(path, child); },
                        [&](detail::ParentReceiver& parent) {
                            for (const IdentityTag& t : identityTags()) {
                                const std::vector<char> text = parent.next();
                                identity.*t.field = std::string(text.begin(), text.end());
                            }
                        });
    return identity;
}

} // namespace vots::fit
