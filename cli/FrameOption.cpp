// The --frame option shared by `fit`, `render` and `verify` for 4D files (fMRI, perfusion, cardiac phases).
#include "FrameOption.h"

#include "vots/fit/VolumeHeader.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace vots::cli {

void addFrameOption(CLI::App& command, std::optional<int>& frame) {
    command.add_option(
        "--frame", frame,
        "Which 3D volume (0-based) of a 4D NIfTI or MGH/MGZ file or a DICOM series with several "
        "time points to read; without it frame 0 is read (and stderr says how many the file holds)");
}

int frameToRead(const std::string& path, const std::optional<fit::RawLayout>& raw, const std::string& series,
                const std::optional<int>& frame) {
    if (frame) return *frame;
    const std::uint64_t frames = fit::volumeHeaderInfo(path, raw, series).frames;
    if (frames > 1)
        std::cerr << "vots: " << path << " holds " << frames
                  << " frames; reading frame 0 (choose one with --frame N)\n";
    return 0;
}

} // namespace vots::cli
