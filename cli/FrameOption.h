// The --frame option of `fit`, `render` and `verify`: picks one 3D volume of a 4D file or DICOM series.
#pragma once

#include "vots/fit/VolumeLoad.h"

#include <climits>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

/// `--frame max`: the temporal MIP, each sample the maximum over the frames (as perfusion CT shows an
/// enhancement), recorded as this frame number (source.frame in the meta block). No frame has it.
inline constexpr int FRAME_MAX = INT_MIN;

/// Adds --frame N (or max) to a command; `frame` stays empty when it is not given.
void addFrameOption(CLI::App& command, std::optional<int>& frame);

/// The frame to read: the one given (the reader refuses one the file does not hold, naming the count),
/// else 0, and then stderr says so when the file holds more than one.
int frameToRead(const std::string& path, const std::optional<fit::RawLayout>& raw, const std::string& series,
                const std::optional<int>& frame);

/// fit::loadVolume of that frame; FRAME_MAX loads the frames one after another (two in memory at a time)
/// into float samples, each the largest finite one over the frames (NaN where every frame has none).
fit::Volume loadFrame(const std::string& path, const std::optional<fit::RawLayout>& raw,
                      fit::SampleStorage storage, const std::string& series, int frame);

} // namespace vots::cli
