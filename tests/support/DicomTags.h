// Reads a DICOM file's elements as text with GDCM, for tests that check what a writer put in a file.
#pragma once

#include <gdcmReader.h>
#include <gdcmStringFilter.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace vots::test {

class DicomTags {
public:
    explicit DicomTags(const std::string& path) {
        mReader.SetFileName(path.c_str());
        if (!mReader.Read()) throw std::runtime_error("GDCM cannot read " + path);
        mFilter.SetFile(mReader.GetFile());
    }
    bool has(std::uint16_t group, std::uint16_t element) const {
        return mReader.GetFile().GetDataSet().FindDataElement(gdcm::Tag(group, element));
    }
    /// The value as text without its padding; "" when absent or empty.
    std::string text(std::uint16_t group, std::uint16_t element) const {
        if (!has(group, element)) return {};
        std::string value = mFilter.ToString(gdcm::Tag(group, element));
        value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
        while (!value.empty() && value.back() == ' ')
            value.pop_back();
        return value;
    }
    /// The file meta information's transfer syntax and SOP class, as text.
    std::string metaText(std::uint16_t group, std::uint16_t element) const {
        const gdcm::FileMetaInformation& meta = mReader.GetFile().GetHeader();
        const gdcm::Tag tag(group, element);
        if (!meta.FindDataElement(tag)) return {};
        const gdcm::ByteValue* bytes = meta.GetDataElement(tag).GetByteValue();
        if (bytes == nullptr) return {};
        std::string value(bytes->GetPointer(), bytes->GetLength());
        value.erase(std::find(value.begin(), value.end(), '\0'), value.end());
        return value;
    }

private:
    gdcm::Reader mReader;
    gdcm::StringFilter mFilter;
};

} // namespace vots::test
