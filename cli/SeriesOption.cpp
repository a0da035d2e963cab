// The --series option shared by `fit`, `render` and `verify` for folders holding several DICOM series.
#include "SeriesOption.h"

#include <CLI/CLI.hpp>

namespace vots::cli {

void addSeriesOption(CLI::App& command, std::string& uid) {
    command.add_option("--series", uid,
                       "SeriesInstanceUID of the DICOM series to read when the input folder holds several "
                       "(the error for such a folder lists them)");
}

} // namespace vots::cli
