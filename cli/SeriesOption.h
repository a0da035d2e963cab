// The --series option of `fit`, `render` and `verify`: picks one DICOM series of a folder by its UID.
#pragma once

#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// Adds --series UID to a command; `uid` stays empty when it is not given (then a folder must hold one).
void addSeriesOption(CLI::App& command, std::string& uid);

} // namespace vots::cli
