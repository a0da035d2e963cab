// libFuzzer target: meta::decodeVotSpace on arbitrary bytes, as given and with the CRC-32 repaired, decodes
// or throws InputError.
#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"
#include "vots/meta/VotSpaceRead.h"

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

void decode(const std::uint8_t* data, std::size_t size) {
    try {
        const vots::fit::VotSpace space = vots::meta::decodeVotSpace(data, size);
        // A file that decodes must encode again (round trip of whatever the decoder accepted).
        (void)vots::fit::encodeVotSpace(space);
    } catch (const vots::fit::InputError&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    decode(data, size);
    // The checksum is tested first, so random bytes rarely get past it: also decode a copy whose last
    // four bytes are the CRC-32 of the rest, which exercises the field and record validation.
    if (size >= 4) {
        std::vector<std::uint8_t> fixed(data, data + size);
        const std::size_t at = size - 4;
        const auto crc =
            static_cast<std::uint32_t>(crc32(crc32(0L, Z_NULL, 0), fixed.data(), static_cast<uInt>(at)));
        for (int i = 0; i < 4; ++i)
            fixed[at + i] = static_cast<std::uint8_t>(crc >> (8 * i));
        decode(fixed.data(), fixed.size());
    }
    return 0;
}
