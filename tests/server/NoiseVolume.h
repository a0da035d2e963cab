// A volume whose fits are slow on any machine, for tests that need a fit still running while they act.
#pragma once

#include "ServerFixture.h"

#include <cstdint>
#include <string>

namespace vots::test {

/// Pseudo-random bytes: no polynomial but a cell's own fits them within a small eps, so a fit at 0.02 runs
/// for seconds on any machine (cancelled when the server stops), and what waits on it stays waiting for the
/// whole test. The smooth test volumes fit in a fraction of a second.
inline constexpr const char* NOISE = "noise_96x96x96_uint8";

/// Writes the noise volume into the world's data folder.
inline void addNoiseVolume(const ServerWorld& world) {
    constexpr int SIDE = 96;
    std::string samples(static_cast<std::size_t>(SIDE) * SIDE * SIDE, '\0');
    std::uint32_t state = 12345u;
    for (char& sample : samples) {
        state = state * 1664525u + 1013904223u; // a fixed LCG: the same volume every run
        sample = static_cast<char>(state >> 24);
    }
    world.dir().write(std::string("data/") + NOISE + ".nrrd",
                      "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 96 96 96\nencoding: raw\n\n" + samples);
}

} // namespace vots::test
