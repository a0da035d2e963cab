// Test-data writer: the bytes of a float32 NIfTI-1 file (3D, or 4D with several frames), little endian.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace vots::test {

/// A .nii of dims[0] x dims[1] x dims[2] samples per frame, `frames` frames one after another in `values`
/// (x fastest), unit spacing, no sform or qform.
inline std::string niftiFloat32(const std::array<int, 3>& dims, int frames,
                                const std::vector<float>& values) {
    std::string bytes(352, '\0');
    const auto put = [&bytes](std::size_t offset, auto value) {
        std::memcpy(bytes.data() + offset, &value, sizeof value);
    };
    put(0, std::int32_t{348});
    const std::int16_t dim[8] = {static_cast<std::int16_t>(frames > 1 ? 4 : 3),
                                 static_cast<std::int16_t>(dims[0]),
                                 static_cast<std::int16_t>(dims[1]),
                                 static_cast<std::int16_t>(dims[2]),
                                 static_cast<std::int16_t>(frames),
                                 1,
                                 1,
                                 1};
    for (std::size_t i = 0; i < 8; ++i)
        put(40 + 2 * i, dim[i]);
    put(70, std::int16_t{16}); // float32
    put(72, std::int16_t{32});
    for (std::size_t i = 0; i < 4; ++i)
        put(76 + 4 * i, 1.f);
    put(108, 352.f);
    std::memcpy(bytes.data() + 344, "n+1\0", 4);
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    return bytes;
}

} // namespace vots::test
