// The --frame option shared by `fit`, `render` and `verify` for 4D files (fMRI, perfusion, cardiac phases).
#include "FrameOption.h"

#include "vots/fit/VolumeHeader.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <iostream>

namespace vots::cli {

void addFrameOption(CLI::App& command, std::optional<int>& frame) {
    command.add_option_function<std::string>(
        "--frame",
        [&frame](const std::string& text) {
            if (text == "max") {
                frame = FRAME_MAX;
                return;
            }
            int value = 0;
            const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
            if (error != std::errc() || end != text.data() + text.size() || value == FRAME_MAX)
                throw CLI::ValidationError("--frame", "'" + text + "' is not a frame number or 'max'");
            frame = value;
        },
        "Which 3D volume (0-based) of a 4D NIfTI or MGH/MGZ file or a DICOM series with several time points "
        "to read, or max (the maximum over the frames at each sample, a temporal MIP); without it frame 0 "
        "is read (and stderr says how many the file holds)");
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

fit::Volume loadFrame(const std::string& path, const std::optional<fit::RawLayout>& raw,
                      fit::SampleStorage storage, const std::string& series, int frame) {
    if (frame != FRAME_MAX) return fit::loadVolume(path, raw, storage, series, frame);
    const std::uint64_t frames = fit::volumeHeaderInfo(path, raw, series).frames;
    fit::Volume most = fit::loadVolume(path, raw, fit::SampleStorage::Float, series, 0);
    for (std::uint64_t k = 1; k < frames; ++k) {
        const fit::Volume next =
            fit::loadVolume(path, raw, fit::SampleStorage::Float, series, static_cast<int>(k));
        for (std::size_t i = 0; i < most.values.size(); ++i)
            most.values[i] = std::fmax(most.values[i], next.values[i]); // fmax passes over a NaN
    }
    return most;
}

} // namespace vots::cli
