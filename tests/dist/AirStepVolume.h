// A generated int16 volume whose air differs between its lower and upper halves along z, so that two
// ranks' cells see different backgrounds: -3000 below, -2980 above, a sphere of 1000 in the middle.
#pragma once

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vots::test {

inline constexpr int AIR_STEP_SIDE = 64;
inline constexpr int AIR_STEP_PLANES = 40;

/// Writes the volume as attached raw NRRD (64 x 64 x 40, unit spacing) to `path`.
inline void writeAirStepVolume(const std::string& path) {
    std::string header = "NRRD0004\ntype: int16\ndimension: 3\nsizes: " + std::to_string(AIR_STEP_SIDE) +
                         " " + std::to_string(AIR_STEP_SIDE) + " " + std::to_string(AIR_STEP_PLANES) +
                         "\nspacings: 1 1 1\nendian: little\nencoding: raw\n\n";
    std::vector<std::int16_t> samples;
    samples.reserve(static_cast<std::size_t>(AIR_STEP_SIDE * AIR_STEP_SIDE * AIR_STEP_PLANES));
    const double centre[3] = {31.5, 31.5, 19.5};
    for (int z = 0; z < AIR_STEP_PLANES; ++z)
        for (int y = 0; y < AIR_STEP_SIDE; ++y)
            for (int x = 0; x < AIR_STEP_SIDE; ++x) {
                const double dx = x - centre[0], dy = y - centre[1], dz = z - centre[2];
                const bool sphere = dx * dx + dy * dy + dz * dz <= 12.0 * 12.0;
                samples.push_back(sphere ? 1000 : (z < AIR_STEP_PLANES / 2 ? -3000 : -2980));
            }
    std::ofstream out(path, std::ios::binary);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(reinterpret_cast<const char*>(samples.data()),
              static_cast<std::streamsize>(samples.size() * sizeof(std::int16_t)));
    if (!out) throw std::runtime_error("cannot write " + path);
}

} // namespace vots::test
