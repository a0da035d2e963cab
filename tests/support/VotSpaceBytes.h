// Test helpers for editing Vot-Space file bytes (docs/DESIGN.md §8) independently of the library's codec.
#pragma once

#include "vots/fit/VotSpace.h"

#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vots::test {

using Bytes = std::vector<std::uint8_t>;

/// Bitwise CRC-32 (reflected polynomial 0xEDB88320, zlib's), written here so the tests check the
/// file's checksum against an implementation that is not the one the codec uses.
inline std::uint32_t referenceCrc32(const std::uint8_t* data, std::size_t size) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; ++bit)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

inline std::uint64_t peekLE(const Bytes& b, std::size_t offset, int width) {
    std::uint64_t v = 0;
    for (int i = 0; i < width; ++i)
        v |= std::uint64_t{b.at(offset + i)} << (8 * i);
    return v;
}

inline void pokeLE(Bytes& b, std::size_t offset, std::uint64_t v, int width) {
    for (int i = 0; i < width; ++i)
        b.at(offset + i) = static_cast<std::uint8_t>(v >> (8 * i));
}

inline void pokeF32(Bytes& b, std::size_t offset, float v) {
    pokeLE(b, offset, std::bit_cast<std::uint32_t>(v), 4);
}
inline void pokeF64(Bytes& b, std::size_t offset, double v) {
    pokeLE(b, offset, std::bit_cast<std::uint64_t>(v), 8);
}
inline float peekF32(const Bytes& b, std::size_t offset) {
    return std::bit_cast<float>(static_cast<std::uint32_t>(peekLE(b, offset, 4)));
}
inline double peekF64(const Bytes& b, std::size_t offset) {
    return std::bit_cast<double>(peekLE(b, offset, 8));
}

/// Recomputes the trailing CRC after an edit, so the check under test is the one that fires.
inline void fixCrc(Bytes& b) {
    const std::size_t at = b.size() - 4;
    pokeLE(b, at, referenceCrc32(b.data(), at), 4);
}

/// A small valid space with varied values: negative numbers, -0.0, UTF-8 meta, eps-varies flag.
inline fit::VotSpace makeSampleSpace(std::size_t votCount = 3) {
    fit::VotSpace s;
    s.dims = {10, 8, 6};
    s.origin = {-12.5, 0.25, 1e-3};
    s.spacing = {0.957, 0.957, 1.5};
    s.degree = 3;
    s.eps = 2.5f;
    s.background = -200.f;
    s.epsVaries = true;
    s.metaJson = "{\"source\":\"Sch\xC3\xA4"
                 "del.nrrd\",\"eps\":2.5}";
    for (std::size_t i = 0; i < votCount; ++i) {
        fit::Vot v;
        const int k = static_cast<int>(i % 4);
        v.box.lo = {k, 0, k % 3};
        v.box.hi = {k + 2 + k % 3, 7, 5};
        v.p = {static_cast<float>(k) + 1.5f, 3.5f, 2.75f};
        v.err = 0.125f * static_cast<float>(i + 1);
        for (std::size_t c = 0; c < v.c.size(); ++c)
            v.c[c] = (c % 5 == 4)
                         ? -0.f
                         : static_cast<float>(c + 1) * (i % 2 ? -1.f : 1.f) / 7.f + static_cast<float>(i);
        s.vots.push_back(v);
    }
    return s;
}

} // namespace vots::test
