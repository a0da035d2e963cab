// Private to the DICOM reader: element values of a GDCM data set as text and as numbers.
#pragma once

#include <gdcmDataSet.h>
#include <gdcmStringFilter.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// The value as text ("" when absent or empty), trimmed; GDCM turns binary VRs (US, UL, ...) into decimal
/// text. `data` may be the file's data set or a sequence item's.
std::string textOf(const gdcm::StringFilter& filter, const gdcm::DataSet& data, std::uint16_t group,
                   std::uint16_t element);

/// Backslash-separated numbers ("0.5\0.5"); nullopt unless there are exactly `count` finite ones.
std::optional<std::vector<double>> numbersOf(const std::string& text, std::size_t count);

} // namespace vots::fit::detail
