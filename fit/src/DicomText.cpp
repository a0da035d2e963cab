// Element values of a GDCM data set as text and as numbers, for the DICOM reader.
#include "DicomText.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace vots::fit::detail {
namespace {

std::string trimmed(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return {};
    const auto last = text.find_last_not_of(" \t\r\n");
    return text.substr(first, last - first + 1);
}

} // namespace

std::string textOf(const gdcm::StringFilter& filter, const gdcm::DataSet& data, std::uint16_t group,
                   std::uint16_t element) {
    const gdcm::Tag tag(group, element);
    if (!data.FindDataElement(tag) || data.GetDataElement(tag).IsEmpty()) return {};
    std::string value = filter.ToString(data.GetDataElement(tag));         // also inside a sequence's item
    value.erase(std::find(value.begin(), value.end(), '\0'), value.end()); // padding of UIDs
    return trimmed(value);
}

std::optional<std::vector<double>> numbersOf(const std::string& text, std::size_t count) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, '\\')) {
        part = trimmed(part);
        char* end = nullptr;
        const double value = std::strtod(part.c_str(), &end);
        if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(value)) return std::nullopt;
        values.push_back(value);
    }
    if (values.size() != count) return std::nullopt;
    return values;
}

} // namespace vots::fit::detail
