// Values of the DICOM JSON model: strings, person names and numbers, tolerant of absent elements.
#include "DicomJson.h"

#include <cstdlib>

namespace vots::pacs {

std::vector<std::string> dicomStrings(const nlohmann::json& dataset, const char* tag) {
    std::vector<std::string> values;
    if (!dataset.is_object()) return values;
    const auto element = dataset.find(tag);
    if (element == dataset.end() || !element->is_object()) return values;
    const auto value = element->find("Value");
    if (value == element->end() || !value->is_array()) return values;
    for (const nlohmann::json& v : *value) {
        if (v.is_string())
            values.push_back(v.get<std::string>());
        else if (v.is_number_integer())
            values.push_back(std::to_string(v.get<long long>()));
        else if (v.is_number())
            values.push_back(v.dump());
        else if (v.is_object() && v.contains("Alphabetic") && v["Alphabetic"].is_string())
            values.push_back(v["Alphabetic"].get<std::string>());
    }
    return values;
}

std::string dicomString(const nlohmann::json& dataset, const char* tag) {
    const std::vector<std::string> values = dicomStrings(dataset, tag);
    return values.empty() ? std::string() : values.front();
}

std::optional<double> dicomNumber(const nlohmann::json& dataset, const char* tag) {
    const std::string text = dicomString(dataset, tag);
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str()) return std::nullopt;
    return value;
}

} // namespace vots::pacs
