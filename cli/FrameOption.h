// The --frame option of `fit`, `render` and `verify`: picks one 3D volume of a 4D file or DICOM series.
#pragma once

#include "vots/fit/VolumeLoad.h"

#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// Adds --frame N to a command; `frame` stays empty when it is not given.
void addFrameOption(CLI::App& command, std::optional<int>& frame);

/// The frame to read: the one given (the reader refuses one the file does not hold, naming the count),
/// else 0, and then stderr says so when the file holds more than one.
int frameToRead(const std::string& path, const std::optional<fit::RawLayout>& raw, const std::string& series,
                const std::optional<int>& frame);

} // namespace vots::cli
