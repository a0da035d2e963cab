// NIfTI-1 and NIfTI-2 headers read into one form (NiftiFields), then checked and interpreted once.
#include "NiftiHeader.h"

#include "InputFile.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace vots::fit::detail {

namespace {

constexpr double MAX_VOX_OFFSET = 1 << 30;

// Header fields read at their fixed offsets with the file's byte order.
class HeaderView {
public:
    HeaderView(const unsigned char* bytes, bool swap) : mBytes(bytes), mSwap(swap) {}

    std::int16_t int16(std::size_t offset) const {
        return std::bit_cast<std::int16_t>(bits<std::uint16_t>(offset));
    }
    std::int32_t int32(std::size_t offset) const {
        return std::bit_cast<std::int32_t>(bits<std::uint32_t>(offset));
    }
    std::int64_t int64(std::size_t offset) const {
        return std::bit_cast<std::int64_t>(bits<std::uint64_t>(offset));
    }
    double float32(std::size_t offset) const { return std::bit_cast<float>(bits<std::uint32_t>(offset)); }
    double float64(std::size_t offset) const { return std::bit_cast<double>(bits<std::uint64_t>(offset)); }

private:
    template <typename U> U bits(std::size_t offset) const {
        U value;
        std::memcpy(&value, mBytes + offset, sizeof(U));
        return mSwap ? byteSwapped(value) : value;
    }

    const unsigned char* mBytes;
    bool mSwap;
};

// The NIfTI-1 layout: int16 dims and codes, float32 pixdim, offsets, scaling and orientation.
void readNifti1(const HeaderView& h, NiftiFields& f) {
    for (std::size_t a = 0; a < 8; ++a) {
        f.dim[a] = h.int16(40 + 2 * a);
        f.pixdim[a] = h.float32(76 + 4 * a);
    }
    f.datatype = h.int16(70);
    f.bitpix = h.int16(72);
    f.voxOffset = h.float32(108);
    f.slope = h.float32(112);
    f.inter = h.float32(116);
    f.qformCode = h.int16(252);
    f.sformCode = h.int16(254);
    for (std::size_t i = 0; i < 3; ++i) {
        f.quatern[i] = h.float32(256 + 4 * i);
        f.qoffset[i] = h.float32(268 + 4 * i);
        for (std::size_t c = 0; c < 4; ++c)
            f.srow[i][c] = h.float32(280 + 16 * i + 4 * c);
    }
}

// The NIfTI-2 layout: the same fields as int64 and float64 at their own offsets.
void readNifti2(const HeaderView& h, NiftiFields& f) {
    for (std::size_t a = 0; a < 8; ++a) {
        f.dim[a] = h.int64(16 + 8 * a);
        f.pixdim[a] = h.float64(104 + 8 * a);
    }
    f.datatype = h.int16(12);
    f.bitpix = h.int16(14);
    f.voxOffset = static_cast<double>(h.int64(168));
    f.slope = h.float64(176);
    f.inter = h.float64(184);
    f.qformCode = h.int32(344);
    f.sformCode = h.int32(348);
    for (std::size_t i = 0; i < 3; ++i) {
        f.quatern[i] = h.float64(352 + 8 * i);
        f.qoffset[i] = h.float64(376 + 8 * i);
        for (std::size_t c = 0; c < 4; ++c)
            f.srow[i][c] = h.float64(400 + 32 * i + 8 * c);
    }
}

// Column a of the sform: grid axis a in RAS, spacing-scaled.
PatientAxes sformDirections(const NiftiFields& f) {
    PatientAxes d{};
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t row = 0; row < 3; ++row)
            d[a][row] = f.srow[row][a];
    return d;
}

// Columns of the qform rotation, the third times qfac (pixdim[0]).
PatientAxes qformDirections(const NiftiFields& f) {
    const double b = f.quatern[0], c = f.quatern[1], d = f.quatern[2];
    const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
    const double qfac = f.pixdim[0] < 0.0 ? -1.0 : 1.0;
    return {{{a * a + b * b - c * c - d * d, 2 * b * c + 2 * a * d, 2 * b * d - 2 * a * c},
             {2 * b * c - 2 * a * d, a * a + c * c - b * b - d * d, 2 * c * d + 2 * a * b},
             {qfac * (2 * b * d + 2 * a * c), qfac * (2 * c * d - 2 * a * b),
              qfac * (a * a + d * d - c * c - b * b)}}};
}

} // namespace

std::size_t niftiHeaderBytes(const std::string& path, const unsigned char* first4) {
    for (const bool swap : {false, true}) {
        const std::int32_t size = HeaderView(first4, swap).int32(0);
        if (size == static_cast<std::int32_t>(NIFTI1_HEADER_BYTES)) return NIFTI1_HEADER_BYTES;
        if (size == static_cast<std::int32_t>(NIFTI2_HEADER_BYTES)) return NIFTI2_HEADER_BYTES;
    }
    throwInputError(path, "not a NIfTI file (sizeof_hdr is neither 348 nor 540)");
}

NiftiFields readNiftiFields(const std::string& path, const unsigned char* bytes) {
    // sizeof_hdr in the file's byte order: that is how NIfTI marks endianness.
    NiftiFields f;
    const std::size_t size = niftiHeaderBytes(path, bytes);
    f.swap = HeaderView(bytes, false).int32(0) != static_cast<std::int32_t>(size);
    f.version = size == NIFTI1_HEADER_BYTES ? 1 : 2;
    const HeaderView h(bytes, f.swap);
    std::memcpy(f.magic.data(), bytes + (f.version == 1 ? 344 : 4), 4);
    if (f.version == 1)
        readNifti1(h, f);
    else
        readNifti2(h, f);
    return f;
}

ScalarType niftiType(const std::string& path, int datatype) {
    switch (datatype) {
    case 2:
        return ScalarType::UInt8;
    case 4:
        return ScalarType::Int16;
    case 8:
        return ScalarType::Int32;
    case 16:
        return ScalarType::Float32;
    case 64:
        return ScalarType::Float64;
    case 256:
        return ScalarType::Int8;
    case 512:
        return ScalarType::UInt16;
    case 768:
        return ScalarType::UInt32;
    default:
        break;
    }
    throwInputError(path, "unsupported NIfTI datatype " + std::to_string(datatype) +
                              " (supported: 2, 4, 8, 16, 64, 256, 512, 768: scalar integers and floats)");
}

std::uint64_t niftiFrames(const std::string& path, const NiftiFields& f) {
    const std::int64_t rank = f.dim[0];
    if (rank < 3 || rank > 7)
        throwInputError(path,
                        "has " + std::to_string(rank) + " dimensions; only 3D and 4D volumes are supported");
    std::uint64_t frames = 1;
    for (std::size_t a = 4; a <= static_cast<std::size_t>(rank); ++a) {
        if (f.dim[a] <= 0 || static_cast<std::uint64_t>(f.dim[a]) > MAX_SAMPLES / frames)
            throwInputError(path, "dim[" + std::to_string(a) + "] is " + std::to_string(f.dim[a]) +
                                      " (must be positive, frames at most " + std::to_string(MAX_SAMPLES) +
                                      ")");
        frames *= static_cast<std::uint64_t>(f.dim[a]);
    }
    return frames;
}

NiftiInfo parseNiftiHeader(const std::string& path, const unsigned char* bytes) {
    const NiftiFields f = readNiftiFields(path, bytes);
    const bool hostBig = std::endian::native == std::endian::big;
    NiftiInfo info;
    info.bigEndian = f.swap != hostBig;
    const std::string magic(f.magic.data(), strnlen(f.magic.data(), f.magic.size()));
    const std::string single = f.version == 1 ? "n+1" : "n+2";
    if (magic == (f.version == 1 ? "ni1" : "ni2"))
        throwInputError(path, "is a NIfTI .hdr/.img pair; only single-file .nii/.nii.gz is supported");
    if (magic != single)
        throwInputError(path,
                        "bad NIfTI-" + std::to_string(f.version) + " magic (expected \"" + single + "\")");

    info.frames = niftiFrames(path, f);
    info.type = niftiType(path, f.datatype);
    if (f.bitpix != static_cast<int>(8 * scalarTypeSize(info.type)))
        throwInputError(path, "bitpix " + std::to_string(f.bitpix) + " does not match datatype " +
                                  std::to_string(f.datatype));
    info.shape = checkShape(path, {f.dim[1], f.dim[2], f.dim[3]}, info.type);
    if (info.frames > MAX_PAYLOAD_BYTES / info.shape.bytes)
        throwInputError(path, std::to_string(info.frames) + " frames of " + std::to_string(info.shape.bytes) +
                                  " bytes exceed the limit of " + std::to_string(MAX_PAYLOAD_BYTES) +
                                  " bytes");

    for (std::size_t a = 0; a < 3; ++a) {
        const double pixdim = f.pixdim[a + 1];
        if (!std::isfinite(pixdim) || pixdim == 0.0)
            throwInputError(path, "pixdim[" + std::to_string(a + 1) + "] is zero or not finite");
        info.spacing[a] = std::fabs(pixdim);
    }

    const std::size_t headerBytes = f.version == 1 ? NIFTI1_HEADER_BYTES : NIFTI2_HEADER_BYTES;
    if (!(f.voxOffset >= static_cast<double>(headerBytes) && f.voxOffset <= MAX_VOX_OFFSET) ||
        f.voxOffset != std::floor(f.voxOffset))
        throwInputError(path, "bad vox_offset " + std::to_string(f.voxOffset));
    info.voxOffset = static_cast<std::uint64_t>(f.voxOffset);

    // Scaling applies when scl_slope is a finite non-zero number other than the identity (1, 0).
    if (std::isfinite(f.slope) && f.slope != 0.0 && !(f.slope == 1.0 && f.inter == 0.0)) {
        if (!std::isfinite(f.inter)) throwInputError(path, "scl_inter is not finite");
        info.slope = f.slope;
        info.inter = f.inter;
    }

    // Origin and axes: the sform when present and spanning space, else the qform, else none (NIfTI
    // method 1). A degenerate sform (some writers set the code with a zero matrix) keeps its translation
    // as the origin, as before orientation was read, but says nothing about the axes.
    const bool sform = f.sformCode > 0, qform = f.qformCode > 0;
    const std::optional<PatientAxes> sformAxes =
        sform ? normalizedPatientAxes(sformDirections(f)) : std::nullopt;
    if (sform && (sformAxes || !qform)) {
        info.origin = {f.srow[0][3], f.srow[1][3], f.srow[2][3]};
        info.axes = sformAxes;
    } else if (qform) {
        info.origin = f.qoffset;
        info.axes = normalizedPatientAxes(qformDirections(f));
        if (!info.axes) throwInputError(path, "qform quaternion is not finite");
    }
    for (const double o : info.origin)
        if (!std::isfinite(o)) throwInputError(path, "origin (qoffset/srow) is not finite");
    if (info.axes) rasToLps(*info.axes, info.origin);
    return info;
}

std::uint64_t frameOffset(const std::string& path, const NiftiInfo& info, int frame) {
    checkFrame(path, frame, info.frames);
    return info.voxOffset + static_cast<std::uint64_t>(frame) * info.shape.bytes;
}

} // namespace vots::fit::detail
