// A volume's samples as headerless little-endian int16 bytes, for the tests of raw input.
#pragma once

#include "vots/fit/Volume.h"

#include <cstdint>
#include <string>

namespace vots::test {

/// Each sample (an integer in int16's range, as the test MRI holds) as two bytes, low byte first.
inline std::string littleEndianInt16Bytes(const fit::Volume& volume) {
    std::string bytes(2 * volume.values.size(), '\0');
    for (std::size_t i = 0; i < volume.values.size(); ++i) {
        const auto sample = static_cast<std::uint16_t>(static_cast<std::int16_t>(volume.values[i]));
        bytes[2 * i] = static_cast<char>(sample & 0xff);
        bytes[2 * i + 1] = static_cast<char>(sample >> 8);
    }
    return bytes;
}

} // namespace vots::test
