// FreeSurfer MGH header: version, dims, frames, type, and vox2ras from spacing, Mdc and c_ras.
#include "MghHeader.h"

#include "InputFile.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace vots::fit::detail {

namespace {

template <typename U> U bigEndianAt(const unsigned char* bytes, std::size_t offset) {
    U value;
    std::memcpy(&value, bytes + offset, sizeof(U));
    return std::endian::native == std::endian::big ? value : byteSwapped(value);
}

std::int32_t int32At(const unsigned char* bytes, std::size_t offset) {
    return std::bit_cast<std::int32_t>(bigEndianAt<std::uint32_t>(bytes, offset));
}

double float32At(const unsigned char* bytes, std::size_t offset) {
    return std::bit_cast<float>(bigEndianAt<std::uint32_t>(bytes, offset));
}

ScalarType mghType(const std::string& path, std::int32_t code) {
    switch (code) {
    case 0:
        return ScalarType::UInt8;
    case 1:
        return ScalarType::Int32;
    case 3:
        return ScalarType::Float32;
    case 4:
        return ScalarType::Int16;
    default:
        break;
    }
    throwInputError(path, "unsupported MGH type " + std::to_string(code) +
                              " (supported: 0 uchar, 1 int, 3 float, 4 short)");
}

} // namespace

MghInfo parseMghHeader(const std::string& path, const unsigned char* bytes) {
    if (int32At(bytes, 0) != 1)
        throwInputError(path,
                        "not an MGH file (version is " + std::to_string(int32At(bytes, 0)) + ", not 1)");
    MghInfo info;
    info.type = mghType(path, int32At(bytes, 20));
    info.shape = checkShape(path, {int32At(bytes, 4), int32At(bytes, 8), int32At(bytes, 12)}, info.type);
    const std::int32_t frames = int32At(bytes, 16);
    if (frames <= 0) throwInputError(path, "nframes is " + std::to_string(frames) + " (must be positive)");
    info.frames = static_cast<std::uint64_t>(frames);
    if (info.frames > MAX_PAYLOAD_BYTES / info.shape.bytes)
        throwInputError(path, std::to_string(info.frames) + " frames of " + std::to_string(info.shape.bytes) +
                                  " bytes exceed the limit of " + std::to_string(MAX_PAYLOAD_BYTES) +
                                  " bytes");

    // Without goodRASFlag the fields are not set: FreeSurfer's default, 1 mm coronal (LIA) about 0.
    PatientAxes ras{{{-1.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}}};
    std::array<double, 3> centre{0.0, 0.0, 0.0};
    const bool goodRas = std::bit_cast<std::int16_t>(bigEndianAt<std::uint16_t>(bytes, 28)) > 0;
    if (goodRas) {
        for (std::size_t a = 0; a < 3; ++a) {
            const double size = float32At(bytes, 30 + 4 * a);
            if (!std::isfinite(size) || !(size > 0.0))
                throwInputError(path, "voxel size " + std::to_string(a + 1) + " is not a finite number > 0");
            info.spacing[a] = size;
            for (std::size_t c = 0; c < 3; ++c) // Mdc holds one axis's RAS direction after another
                ras[a][c] = float32At(bytes, 42 + 12 * a + 4 * c);
            centre[a] = float32At(bytes, 78 + 4 * a);
        }
        const auto axes = normalizedPatientAxes(ras);
        if (!axes) throwInputError(path, "direction cosines (Mdc) are not finite or do not span space");
        // vox2ras scales each Mdc column by the voxel size as it stands, unit length or not: the grid
        // step along an axis is their product.
        for (std::size_t a = 0; a < 3; ++a)
            info.spacing[a] *= std::hypot(ras[a][0], ras[a][1], ras[a][2]);
        ras = *axes;
        for (const double c : centre)
            if (!std::isfinite(c)) throwInputError(path, "c_ras is not finite");
    }
    // vox2ras: c_ras is the world position of the grid's centre, index dims / 2 (FreeSurfer's Pcrs_c).
    for (std::size_t c = 0; c < 3; ++c) {
        double origin = centre[c];
        for (std::size_t a = 0; a < 3; ++a)
            origin -= ras[a][c] * info.spacing[a] * info.shape.dims[a] / 2.0;
        info.origin[c] = origin;
    }
    info.axes = ras;
    rasToLps(info.axes, info.origin);
    return info;
}

} // namespace vots::fit::detail
