// Header-only reading of NRRD, NIfTI, MGH and MetaImage files: the announced dims and sample type, no
// samples. The readers (NrrdReader.cpp, ...) validate everything else when the volume is loaded; this file
// reads just the fields that size the load, in the same way, so both agree on the grid.
#include "vots/fit/VolumeHeader.h"

#include "Gzip.h"
#include "HeaderText.h"
#include "InputFile.h"
#include "MghHeader.h"
#include "NiftiHeader.h"
#include "SampleDecode.h"

#include "vots/fit/DicomSeries.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>

namespace vots::fit {

namespace {

using namespace detail;

constexpr std::size_t MAX_TEXT_HEADER_BYTES = std::size_t{1} << 20; // as the NRRD and MetaImage readers
constexpr std::size_t GZIP_PREFIX_BYTES = std::size_t{1} << 16;     // far more than 348 inflated bytes need

std::uint64_t saturatingProduct(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
        return std::numeric_limits<std::uint64_t>::max();
    return a * b;
}

VolumeHeaderInfo infoFrom(const std::string& path, const std::array<long long, 3>& dims, ScalarType type) {
    VolumeHeaderInfo info;
    info.sourceType = type;
    for (int a = 0; a < 3; ++a) {
        if (dims[a] <= 0)
            throwInputError(path, std::string("size along ") + "xyz"[a] + " is " + std::to_string(dims[a]) +
                                      " (must be positive)");
        info.dims[a] = static_cast<std::uint64_t>(dims[a]);
    }
    return info;
}

// "key: value" lines after the magic line, up to the blank line before attached data.
VolumeHeaderInfo nrrdInfo(const std::string& path) {
    const std::string text = readFilePrefix(path, MAX_TEXT_HEADER_BYTES);
    if (text.size() < 8 || text.compare(0, 7, "NRRD000") != 0)
        throwInputError(path, "not a NRRD file (it does not start with NRRD000x)");
    std::string type, sizes, dimension;
    HeaderLine line = lineAt(text, 0);
    while (line.next < text.size()) {
        line = lineAt(text, line.next);
        if (line.text.empty()) break;
        if (line.text.front() == '#' || line.text.find(":=") != std::string::npos) continue;
        const std::size_t colon = line.text.find(':');
        if (colon == std::string::npos) continue; // the reader names a bad line when it loads
        const std::string key = toLower(trim(line.text.substr(0, colon)));
        const std::string value = trim(line.text.substr(colon + 1));
        if (key == "type") type = value;
        if (key == "sizes") sizes = value;
        if (key == "dimension") dimension = value;
        if (key == "data file" || key == "datafile") {
            // A LIST of names follows to the end of the header; nothing after it sizes the volume.
            const std::vector<std::string> words = splitWords(value);
            if (!words.empty() && words[0] == "LIST") break;
        }
    }
    const long long rank = parseIntegers(path, "dimension", dimension, 1)[0];
    if (rank != 3)
        throwInputError(path, "dimension is " + std::to_string(rank) + "; only 3D volumes are supported");
    const std::optional<ScalarType> scalar = findScalarType(type);
    if (!scalar) throwInputError(path, "missing or unsupported 'type' field '" + quotable(type) + "'");
    const std::vector<long long> n = parseIntegers(path, "sizes", sizes, 3);
    return infoFrom(path, {n[0], n[1], n[2]}, *scalar);
}

// "Key = Value" lines up to ElementDataFile, which always comes last.
VolumeHeaderInfo metaImageInfo(const std::string& path) {
    static const std::map<std::string, ScalarType> TYPES = {
        {"MET_UCHAR", ScalarType::UInt8},   {"MET_CHAR", ScalarType::Int8},
        {"MET_USHORT", ScalarType::UInt16}, {"MET_SHORT", ScalarType::Int16},
        {"MET_UINT", ScalarType::UInt32},   {"MET_INT", ScalarType::Int32},
        {"MET_FLOAT", ScalarType::Float32}, {"MET_DOUBLE", ScalarType::Float64}};
    const std::string text = readFilePrefix(path, MAX_TEXT_HEADER_BYTES);
    std::map<std::string, std::string> fields;
    std::size_t offset = 0;
    while (offset < text.size()) {
        const HeaderLine line = lineAt(text, offset);
        offset = line.next;
        const std::size_t equals = line.text.find('=');
        if (equals == std::string::npos || line.text.front() == '#') continue;
        const std::string key = toLower(trim(line.text.substr(0, equals)));
        fields[key] = trim(line.text.substr(equals + 1));
        if (key == "elementdatafile") break;
    }
    if (!fields.count("ndims") || !fields.count("dimsize") || !fields.count("elementtype"))
        throwInputError(path, "not a MetaImage header with NDims, DimSize and ElementType");
    const long long rank = parseIntegers(path, "NDims", fields["ndims"], 1)[0];
    if (rank != 3)
        throwInputError(path, "NDims is " + std::to_string(rank) + "; only 3D volumes are supported");
    const auto type = TYPES.find(fields["elementtype"]);
    if (type == TYPES.end())
        throwInputError(path, "unsupported ElementType '" + quotable(fields["elementtype"]) + "'");
    const std::vector<long long> n = parseIntegers(path, "DimSize", fields["dimsize"], 3);
    return infoFrom(path, {n[0], n[1], n[2]}, type->second);
}

// The first `count` bytes of the file, inflated when it is gzip (.nii.gz, .mgz).
std::vector<unsigned char> headerBytes(const std::string& path, std::size_t count) {
    const std::uint64_t fileSize = regularFileSize(path);
    const std::vector<unsigned char> start = readFileBytes(path, 0, fileSize < 2 ? 0 : 2);
    if (!hasGzipMagic(start.data(), start.size())) {
        if (fileSize < count)
            throwInputError(path, "too short for its header (" + std::to_string(fileSize) + " bytes)");
        return readFileBytes(path, 0, count);
    }
    const auto prefix = readFileBytes(
        path, 0, static_cast<std::size_t>(std::min<std::uint64_t>(fileSize, GZIP_PREFIX_BYTES)));
    Inflater inflater(path, prefix.data(), prefix.size());
    return inflater.readExactly(count);
}

// The NIfTI-1 or NIfTI-2 fields that size the load, read as the reader reads them (NiftiHeader.cpp).
VolumeHeaderInfo niftiInfo(const std::string& path) {
    const std::vector<unsigned char> first = headerBytes(path, 4);
    const std::vector<unsigned char> header = headerBytes(path, niftiHeaderBytes(path, first.data()));
    const NiftiFields fields = readNiftiFields(path, header.data());
    VolumeHeaderInfo info =
        infoFrom(path, {fields.dim[1], fields.dim[2], fields.dim[3]}, niftiType(path, fields.datatype));
    info.frames = niftiFrames(path, fields);
    // As the reader decides: a finite non-zero scl_slope other than the identity (1, 0) scales to floats.
    info.scaled =
        std::isfinite(fields.slope) && fields.slope != 0.0 && !(fields.slope == 1.0 && fields.inter == 0.0);
    return info;
}

// FreeSurfer's header: dims, frames and type.
VolumeHeaderInfo mghInfo(const std::string& path) {
    const std::vector<unsigned char> header = headerBytes(path, MGH_HEADER_BYTES);
    const MghInfo mgh = parseMghHeader(path, header.data());
    VolumeHeaderInfo info =
        infoFrom(path, {mgh.shape.dims[0], mgh.shape.dims[1], mgh.shape.dims[2]}, mgh.type);
    info.frames = mgh.frames;
    return info;
}

} // namespace

std::uint64_t VolumeHeaderInfo::sampleCount() const {
    return saturatingProduct(saturatingProduct(dims[0], dims[1]), dims[2]);
}

std::uint64_t VolumeHeaderInfo::storedBytes() const {
    return saturatingProduct(sampleCount(), scalarTypeSize(sourceType));
}

std::string VolumeHeaderInfo::describe() const {
    return std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + " " +
           scalarTypeName(sourceType);
}

VolumeHeaderInfo volumeHeaderInfo(const std::string& path, const std::optional<RawLayout>& raw,
                                  const std::string& dicomSeries) {
    if (raw) return infoFrom(path, {raw->dims[0], raw->dims[1], raw->dims[2]}, raw->type);
    if (isDicomFolder(path)) return dicomSeriesHeaderInfo(path, dicomSeries);
    const std::string extension = volumeExtension(path);
    if (extension == ".nrrd" || extension == ".nhdr") return nrrdInfo(path);
    if (extension == ".nii" || extension == ".nii.gz") return niftiInfo(path);
    if (extension == ".mgh" || extension == ".mgz") return mghInfo(path);
    if (extension == ".mhd" || extension == ".mha") return metaImageInfo(path);
    throwUnknownVolumeFormat(path);
}

} // namespace vots::fit
