// CRC-32 (zlib's polynomial) over buffers of any size, chainable.
#pragma once

#include <zlib.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace vots::fit {

/// crc extended by `size` bytes at `data`; start a new CRC with crc = 0. zlib takes uInt lengths, so
/// large buffers go in chunks.
inline std::uint32_t crc32Update(std::uint32_t crc, const void* data, std::size_t size) {
    uLong value = crc;
    const auto* bytes = static_cast<const Bytef*>(data);
    while (size > 0) {
        const auto chunk = static_cast<uInt>(std::min<std::size_t>(size, 1u << 30));
        value = crc32(value, bytes, chunk);
        bytes += chunk;
        size -= chunk;
    }
    return static_cast<std::uint32_t>(value);
}

} // namespace vots::fit
