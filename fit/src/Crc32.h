// CRC-32 (the zlib / gzip polynomial) over buffers of any size, chainable.
#pragma once

#include <libdeflate.h>

#include <cstddef>
#include <cstdint>

namespace vots::fit {

/// crc extended by `size` bytes at `data`; start a new CRC with crc = 0. libdeflate takes size_t
/// lengths (zlib's crc32 needed chunks of uInt) and gives the same values as zlib.
inline std::uint32_t crc32Update(std::uint32_t crc, const void* data, std::size_t size) {
    return libdeflate_crc32(crc, data, size);
}

} // namespace vots::fit
