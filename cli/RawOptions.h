// The --raw-* options shared by `fit`, `verify` and `render` for headerless volumes; no loading here.
#pragma once

#include "vots/fit/VolumeLoad.h"

#include <cstddef>
#include <optional>
#include <string>

namespace CLI {
class App;
}

namespace vots::cli {

struct RawArgs {
    std::string dims;    // "X,Y,Z"
    std::string type;    // "int16", "uint8", ...
    std::string spacing; // "sx,sy,sz"
    bool bigEndian = false;
    std::size_t headerBytes = 0;
};

/// Adds --raw-dims, --raw-type, --raw-spacing, --raw-big-endian, --raw-header-bytes to a command.
void addRawOptions(CLI::App& command, RawArgs& args);

/// The layout when any --raw-* option was given (then --raw-dims and --raw-type are required),
/// else nullopt. Throws InputError.
std::optional<fit::RawLayout> rawLayoutFrom(const RawArgs& args);

} // namespace vots::cli
