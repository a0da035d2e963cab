// Reads single-file NIfTI-1 volumes (.nii, .nii.gz) of either byte order; no NIfTI-2, pairs or 4D series.
#include "vots/fit/VolumeLoad.h"

#include "vots/fit/PatientAxes.h"

#include "Gzip.h"
#include "GzipPlanes.h"
#include "InputFile.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

namespace vots::fit {

namespace {

using namespace detail;

constexpr std::size_t HEADER_BYTES = 348;
constexpr double MAX_VOX_OFFSET = 1 << 30;

// The NIfTI-1 header fields we use, read at their fixed offsets with the file's byte order.
class HeaderView {
public:
    HeaderView(const unsigned char* bytes, bool swap) : mBytes(bytes), mSwap(swap) {}

    std::int16_t int16(std::size_t offset) const {
        return std::bit_cast<std::int16_t>(bits<std::uint16_t>(offset));
    }
    std::int32_t int32(std::size_t offset) const {
        return std::bit_cast<std::int32_t>(bits<std::uint32_t>(offset));
    }
    float float32(std::size_t offset) const { return std::bit_cast<float>(bits<std::uint32_t>(offset)); }

private:
    template <typename U> U bits(std::size_t offset) const {
        U value;
        std::memcpy(&value, mBytes + offset, sizeof(U));
        return mSwap ? byteSwapped(value) : value;
    }

    const unsigned char* mBytes;
    bool mSwap;
};

struct NiftiInfo {
    CheckedShape shape;
    ScalarType type = ScalarType::UInt8;
    bool bigEndian = false;
    std::size_t voxOffset = 0;
    double slope = 0.0; // 0: no scaling
    double inter = 0.0;
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    std::optional<PatientAxes> axes; // in LPS; nullopt: neither sform nor qform (NIfTI method 1)
};

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

// Column a of the sform (srow_x, srow_y, srow_z at 280, 296, 312): grid axis a in RAS, spacing-scaled.
PatientAxes sformDirections(const HeaderView& h) {
    PatientAxes d{};
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t row = 0; row < 3; ++row)
            d[a][row] = h.float32(280 + 16 * row + 4 * a);
    return d;
}

// Columns of the qform rotation (quatern_b, c, d at 256, 260, 264), the third times qfac (pixdim[0]).
PatientAxes qformDirections(const HeaderView& h) {
    const double b = h.float32(256), c = h.float32(260), d = h.float32(264);
    const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
    const double qfac = h.float32(76) < 0.0f ? -1.0 : 1.0;
    return {{{a * a + b * b - c * c - d * d, 2 * b * c + 2 * a * d, 2 * b * d - 2 * a * c},
             {2 * b * c - 2 * a * d, a * a + c * c - b * b - d * d, 2 * c * d + 2 * a * b},
             {qfac * (2 * b * d + 2 * a * c), qfac * (2 * c * d - 2 * a * b),
              qfac * (a * a + d * d - c * c - b * b)}}};
}

NiftiInfo parseHeader(const std::string& path, const unsigned char* bytes) {
    // sizeof_hdr is 348 in the file's byte order: that is how NIfTI marks endianness.
    const bool hostBig = std::endian::native == std::endian::big;
    NiftiInfo info;
    bool swap = false;
    if (HeaderView(bytes, false).int32(0) == 348)
        swap = false;
    else if (HeaderView(bytes, true).int32(0) == 348)
        swap = true;
    else if (HeaderView(bytes, false).int32(0) == 540 || HeaderView(bytes, true).int32(0) == 540)
        throwInputError(path, "is NIfTI-2, which is not supported (only NIfTI-1)");
    else
        throwInputError(path, "not a NIfTI-1 file (sizeof_hdr is not 348)");
    info.bigEndian = swap != hostBig;
    const HeaderView h(bytes, swap);

    if (std::memcmp(bytes + 344, "ni1", 4) == 0)
        throwInputError(path, "is a NIfTI .hdr/.img pair; only single-file .nii/.nii.gz is supported");
    if (std::memcmp(bytes + 344, "n+1", 4) != 0)
        throwInputError(path, "bad NIfTI-1 magic (expected \"n+1\")");

    const int rank = h.int16(40);
    if (rank < 3 || rank > 7)
        throwInputError(path, "has " + std::to_string(rank) + " dimensions; only 3D volumes are supported");
    for (int a = 4; a <= rank; ++a)
        if (h.int16(40 + 2 * a) != 1)
            throwInputError(path, "dim[" + std::to_string(a) + "] is " + std::to_string(h.int16(40 + 2 * a)) +
                                      "; only 3D volumes are supported");

    info.type = niftiType(path, h.int16(70));
    const int bitpix = h.int16(72);
    if (bitpix != static_cast<int>(8 * scalarTypeSize(info.type)))
        throwInputError(path, "bitpix " + std::to_string(bitpix) + " does not match datatype " +
                                  std::to_string(h.int16(70)));
    info.shape = checkShape(path, {h.int16(42), h.int16(44), h.int16(46)}, info.type);

    for (int a = 0; a < 3; ++a) {
        const float pixdim = h.float32(80 + 4 * static_cast<std::size_t>(a));
        if (!std::isfinite(pixdim) || pixdim == 0.0f)
            throwInputError(path, "pixdim[" + std::to_string(a + 1) + "] is zero or not finite");
        info.spacing[a] = std::fabs(static_cast<double>(pixdim));
    }

    const double voxOffset = h.float32(108);
    if (!(voxOffset >= HEADER_BYTES && voxOffset <= MAX_VOX_OFFSET) || voxOffset != std::floor(voxOffset))
        throwInputError(path, "bad vox_offset " + std::to_string(voxOffset));
    info.voxOffset = static_cast<std::size_t>(voxOffset);

    // Scaling applies when scl_slope is a finite non-zero number other than the identity (1, 0).
    const double slope = h.float32(112);
    const double inter = h.float32(116);
    if (std::isfinite(slope) && slope != 0.0 && !(slope == 1.0 && inter == 0.0)) {
        if (!std::isfinite(inter)) throwInputError(path, "scl_inter is not finite");
        info.slope = slope;
        info.inter = inter;
    }

    // Origin and axes: the sform when present and spanning space, else the qform, else none (NIfTI
    // method 1). A degenerate sform (some writers set the code with a zero matrix) keeps its translation
    // as the origin, as before orientation was read, but says nothing about the axes.
    const bool sform = h.int16(254) > 0, qform = h.int16(252) > 0;
    const std::optional<PatientAxes> sformAxes =
        sform ? normalizedPatientAxes(sformDirections(h)) : std::nullopt;
    if (sform && (sformAxes || !qform)) {
        info.origin = {h.float32(292), h.float32(308), h.float32(324)};
        info.axes = sformAxes;
    } else if (qform) {
        info.origin = {h.float32(268), h.float32(272), h.float32(276)};
        info.axes = normalizedPatientAxes(qformDirections(h));
        if (!info.axes) throwInputError(path, "qform quaternion is not finite");
    }
    for (const double o : info.origin)
        if (!std::isfinite(o)) throwInputError(path, "origin (qoffset/srow) is not finite");
    if (info.axes) { // NIfTI's patient space is RAS, ours is LPS: the first two coordinates change sign
        for (auto& axis : *info.axes)
            for (int c = 0; c < 2; ++c)
                axis[c] = axis[c] == 0.0 ? 0.0 : -axis[c];
        for (int c = 0; c < 2; ++c)
            info.origin[c] = info.origin[c] == 0.0 ? 0.0 : -info.origin[c];
    }
    return info;
}

// Everything but the samples, from the header.
Volume gridOf(const std::string& path, const NiftiInfo& info) {
    Volume volume;
    volume.dims = info.shape.dims;
    volume.spacing = info.spacing;
    volume.origin = info.origin;
    if (info.axes) {
        volume.patientAxes = *info.axes;
        volume.orientationKnown = true;
    }
    volume.sourceType = info.type;
    volume.name = fileStem(path);
    return volume;
}

bool isGzipped(const std::string& path, std::uint64_t fileSize) {
    const std::vector<unsigned char> magic = readFileBytes(path, 0, fileSize < 2 ? 0 : 2);
    return hasGzipMagic(magic.data(), magic.size());
}

StoredSamples storedPlain(const std::string& path, std::uint64_t fileSize) {
    if (fileSize < HEADER_BYTES)
        throwInputError(path, "too short for a NIfTI-1 header (" + std::to_string(fileSize) + " bytes)");
    const std::vector<unsigned char> header = readFileBytes(path, 0, HEADER_BYTES);
    const NiftiInfo info = parseHeader(path, header.data());
    const std::uint64_t expected = info.voxOffset + static_cast<std::uint64_t>(info.shape.bytes);
    if (fileSize > expected)
        throwInputError(path, "holds " + std::to_string(fileSize) + " bytes but the header describes " +
                                  std::to_string(expected) + " (wrong dims or datatype?)");
    StoredSamples stored;
    stored.grid = gridOf(path, info);
    stored.type = info.type;
    stored.bigEndian = info.bigEndian;
    stored.pieces.push_back({path, info.voxOffset, info.shape.bytes});
    stored.slope = info.slope;
    stored.inter = info.inter;
    return stored;
}

} // namespace

std::optional<StoredSamples> detail::storedNiftiSamples(const std::string& path) {
    const std::uint64_t fileSize = regularFileSize(path);
    if (isGzipped(path, fileSize)) return std::nullopt;
    return storedPlain(path, fileSize);
}

std::optional<GzipSamples> detail::gzipNiftiSamples(const std::string& path) {
    if (!isGzipped(path, regularFileSize(path))) return std::nullopt;
    // The header is the stream's first bytes; the samples start at vox_offset of the decompressed file.
    Inflater inflater(path, path, 0);
    const std::vector<unsigned char> header = inflater.readExactly(HEADER_BYTES);
    const NiftiInfo info = parseHeader(path, header.data());
    GzipSamples stored;
    stored.grid = gridOf(path, info);
    stored.type = info.type;
    stored.bigEndian = info.bigEndian;
    stored.pieces.push_back({path, 0, info.voxOffset, info.shape.bytes, std::nullopt});
    stored.slope = info.slope;
    stored.inter = info.inter;
    return stored;
}

void detail::applyScaling(const std::string& path, std::vector<float>& values, double slope, double inter) {
    std::size_t bad = 0;
    for (float& v : values) {
        const double scaled = v * slope + inter;
        const bool ok = std::fabs(scaled) <= std::numeric_limits<float>::max();
        bad += ok ? 0 : 1;
        v = ok ? static_cast<float>(scaled) : 0.0f;
    }
    if (bad > 0)
        throwInputError(path, std::to_string(bad) + " samples leave float range after scl_slope/scl_inter");
}

Volume loadNifti(const std::string& path, SampleStorage storage) {
    const std::uint64_t fileSize = regularFileSize(path);
    if (!isGzipped(path, fileSize)) return readStoredVolume(path, storedPlain(path, fileSize), storage);
    const GzipSamples stored = *gzipNiftiSamples(path);
    return readGzipPlanes(path, stored, 0, stored.grid.dims[2] - 1, storage);
}

} // namespace vots::fit
