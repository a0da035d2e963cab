// Reading values out of the DICOM JSON model (PS3.18 F.2) that QIDO-RS and WADO-RS metadata answer with.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace vots::pacs {

/// The element's values as text (a person name's Alphabetic part; numbers printed); empty when absent.
std::vector<std::string> dicomStrings(const nlohmann::json& dataset, const char* tag);
/// The first of dicomStrings, or empty.
std::string dicomString(const nlohmann::json& dataset, const char* tag);
/// The first value as a number (numbers and numeric strings, IS and DS), or nullopt.
std::optional<double> dicomNumber(const nlohmann::json& dataset, const char* tag);

} // namespace vots::pacs
