// Reads MetaImage volumes (.mhd + data file, or .mha with LOCAL data), raw or zlib-compressed, 3D scalars.
#include "vots/fit/VolumeLoad.h"

#include "vots/fit/PatientAxes.h"

#include "vots/fit/Error.h"

#include "GzipPlanes.h"
#include "HeaderText.h"
#include "InputFile.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

namespace vots::fit {

namespace {

using namespace detail;

constexpr std::size_t MAX_HEADER_BYTES = std::size_t{1} << 20;

struct MetaHeader {
    std::map<std::string, std::string> fields; // key in lower case -> value
    std::uint64_t localDataOffset = 0;         // just past the ElementDataFile line
};

MetaHeader parseHeader(const std::string& path, const std::string& text, std::uint64_t fileSize) {
    MetaHeader header;
    std::size_t offset = 0;
    while (offset < text.size()) {
        const HeaderLine line = lineAt(text, offset);
        if (!line.complete && text.size() < fileSize)
            throwInputError(path, "header is longer than " + std::to_string(MAX_HEADER_BYTES) + " bytes");
        offset = line.next;
        if (trim(line.text).empty() || line.text.front() == '#') continue;
        const std::size_t equals = line.text.find('=');
        if (equals == std::string::npos)
            throwInputError(path, "bad header line '" + quotable(line.text) + "'");
        const std::string key = toLower(trim(line.text.substr(0, equals)));
        header.fields[key] = trim(line.text.substr(equals + 1));
        // ElementDataFile is always the last field; LOCAL data starts on the next byte.
        if (key == "elementdatafile") {
            header.localDataOffset = line.next;
            return header;
        }
    }
    throwInputError(path, "not a MetaImage header (no ElementDataFile field)");
}

const std::string* field(const MetaHeader& header, const std::string& key) {
    const auto it = header.fields.find(key);
    return it == header.fields.end() ? nullptr : &it->second;
}

bool booleanField(const std::string& path, const MetaHeader& header, const std::string& key) {
    const std::string* value = field(header, key);
    if (!value) return false;
    const std::string lower = toLower(*value);
    if (lower == "true" || lower == "1") return true;
    if (lower == "false" || lower == "0") return false;
    throwInputError(path, "'" + key + "' must be True or False, got '" + quotable(*value) + "'");
}

ScalarType metaType(const std::string& path, const std::string& name) {
    static const std::map<std::string, ScalarType> TYPES = {
        {"MET_UCHAR", ScalarType::UInt8},   {"MET_CHAR", ScalarType::Int8},
        {"MET_USHORT", ScalarType::UInt16}, {"MET_SHORT", ScalarType::Int16},
        {"MET_UINT", ScalarType::UInt32},   {"MET_INT", ScalarType::Int32},
        {"MET_FLOAT", ScalarType::Float32}, {"MET_DOUBLE", ScalarType::Float64}};
    const auto it = TYPES.find(name);
    if (it == TYPES.end())
        throwInputError(path,
                        "unsupported ElementType '" + quotable(name) +
                            "' (supported: MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_UINT, MET_INT, "
                            "MET_FLOAT, MET_DOUBLE)");
    return it->second;
}

std::array<double, 3> spacingOf(const std::string& path, const MetaHeader& header) {
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    for (const char* key : {"elementspacing", "elementsize"}) {
        if (const std::string* value = field(header, key)) {
            const std::vector<double> numbers = parseReals(path, key, *value, 3);
            for (int a = 0; a < 3; ++a)
                spacing[a] = checkedSpacing(path, key, numbers[a]);
            break;
        }
    }
    return spacing;
}

std::array<double, 3> originOf(const std::string& path, const MetaHeader& header) {
    for (const char* key : {"offset", "position", "origin"}) {
        if (const std::string* value = field(header, key)) {
            const std::vector<double> numbers = parseReals(path, key, *value, 3);
            for (const double n : numbers)
                if (!std::isfinite(n)) throwInputError(path, "'" + std::string(key) + "' is not finite");
            return {numbers[0], numbers[1], numbers[2]};
        }
    }
    return {0.0, 0.0, 0.0};
}

// AnatomicalOrientation in ITK's sense (ITK writes "RAI" for the identity in LPS): each letter names
// the side where the axis starts, so the axis grows towards the opposite side.
std::optional<PatientAxes> axesFromLetters(const std::string& path, const std::string& letters) {
    const std::string text = toLower(trim(letters));
    PatientAxes directions{};
    if (text.size() != 3)
        throwInputError(path, "AnatomicalOrientation must be three letters, got '" + quotable(letters) + "'");
    for (std::size_t a = 0; a < 3; ++a) {
        static const std::string FROM = "rlapis"; // from R grows to +L, from L to -L, ...
        const std::size_t at = FROM.find(text[a]);
        if (at == std::string::npos)
            throwInputError(path, "AnatomicalOrientation letters are R, L, A, P, I, S; got '" +
                                      quotable(letters) + "'");
        directions[a][at / 2] = at % 2 == 0 ? 1.0 : -1.0;
    }
    const auto axes = normalizedPatientAxes(directions);
    if (!axes)
        throwInputError(path, "AnatomicalOrientation '" + quotable(letters) + "' names one direction twice");
    return axes;
}

// TransformMatrix (or its other names Rotation, Orientation) wins over AnatomicalOrientation: it is what
// ITK reads back, the letters are only a summary of it. Triplet a is grid axis a in LPS.
std::optional<PatientAxes> axesOf(const std::string& path, const MetaHeader& header) {
    for (const char* key : {"transformmatrix", "rotation", "orientation"}) {
        if (const std::string* value = field(header, key)) {
            const std::vector<double> numbers = parseReals(path, key, *value, 9);
            PatientAxes directions{};
            for (std::size_t a = 0; a < 3; ++a)
                for (std::size_t c = 0; c < 3; ++c)
                    directions[a][c] = numbers[3 * a + c];
            const auto axes = normalizedPatientAxes(directions);
            if (!axes)
                throwInputError(path, "'" + std::string(key) + "' is not finite or does not span space");
            return axes;
        }
    }
    if (const std::string* letters = field(header, "anatomicalorientation"))
        if (!trim(*letters).empty() && letters->find('?') == std::string::npos) // "???": unknown
            return axesFromLetters(path, *letters);
    return std::nullopt;
}

// Where the payload lies: its file, and whether (and how) it is compressed.
struct MetaPayload {
    std::string file;
    std::uint64_t start = 0; // raw: the first sample byte; compressed: the first packed byte
    bool compressed = false;
    std::uint64_t packedSize = 0; // compressed only
};

MetaPayload locatePayload(const std::string& path, const MetaHeader& header, std::size_t bytes) {
    const std::string& name = header.fields.at("elementdatafile");
    if (name.empty()) throwInputError(path, "ElementDataFile is empty");
    if (name == "LIST" || (name.find('%') != std::string::npos && splitWords(name).size() > 1))
        throwInputError(path, "multi-file ElementDataFile '" + quotable(name) + "' is not supported");
    const bool local = toLower(name) == "local";
    MetaPayload payload;
    payload.file = local ? path : pathBesideHeader(path, name);
    const std::string& file = payload.file;
    std::uint64_t size = 0;
    try {
        size = regularFileSize(file);
    } catch (const InputError& error) {
        throwInputError(path, "data file '" + name + "' cannot be used (" + error.what() + ")");
    }
    std::uint64_t start = local ? header.localDataOffset : 0;
    long long headerSize = 0;
    if (const std::string* value = field(header, "headersize"))
        headerSize = parseIntegers(path, "HeaderSize", *value, 1)[0];
    if (headerSize < -1) throwInputError(path, "HeaderSize must be -1 or at least 0");

    if (booleanField(path, header, "compresseddata")) {
        if (headerSize < 0) throwInputError(path, "HeaderSize -1 cannot be used with CompressedData");
        start += static_cast<std::uint64_t>(headerSize);
        if (start > size) throwInputError(file, "truncated: the compressed data would start past the end");
        std::uint64_t packedSize = size - start;
        if (const std::string* value = field(header, "compresseddatasize")) {
            const long long claimed = parseIntegers(path, "CompressedDataSize", *value, 1)[0];
            if (claimed <= 0) throwInputError(path, "CompressedDataSize must be positive");
            if (static_cast<std::uint64_t>(claimed) > packedSize)
                throwInputError(file, "truncated: CompressedDataSize is " + std::to_string(claimed) +
                                          " but only " + std::to_string(packedSize) + " bytes follow");
            packedSize = static_cast<std::uint64_t>(claimed);
        }
        payload.start = start;
        payload.compressed = true;
        payload.packedSize = packedSize;
        return payload;
    }
    // HeaderSize -1: the samples are the last bytes of the file.
    start =
        headerSize < 0 ? (size >= bytes ? size - bytes : 0) : start + static_cast<std::uint64_t>(headerSize);
    const std::uint64_t have = size > start ? size - start : 0;
    if (have > bytes)
        throwInputError(file, "holds " + std::to_string(have) + " data bytes but the header describes " +
                                  std::to_string(bytes) + " (wrong DimSize or ElementType?)");
    payload.start = start;
    return payload;
}

// A MetaImage file whose header passed every check.
struct MetaFile {
    SampleFormat format; // the grid has no samples yet
    CheckedShape shape;
    MetaPayload payload;
};

MetaFile openMetaImage(const std::string& path) {
    const std::uint64_t fileSize = regularFileSize(path);
    const MetaHeader header = parseHeader(path, readFilePrefix(path, MAX_HEADER_BYTES), fileSize);

    if (const std::string* object = field(header, "objecttype"); object && toLower(*object) != "image")
        throwInputError(path, "ObjectType is '" + quotable(*object) + "', not Image");
    const std::string* ndims = field(header, "ndims");
    if (!ndims) throwInputError(path, "missing NDims");
    const long long rank = parseIntegers(path, "NDims", *ndims, 1)[0];
    if (rank != 3)
        throwInputError(path, "NDims is " + std::to_string(rank) + "; only 3D volumes are supported");
    if (const std::string* channels = field(header, "elementnumberofchannels");
        channels && parseIntegers(path, "ElementNumberOfChannels", *channels, 1)[0] != 1)
        throwInputError(path, "ElementNumberOfChannels must be 1 (scalar volumes only)");
    if (const std::string* binary = field(header, "binarydata");
        binary && !booleanField(path, header, "binarydata"))
        throwInputError(path, "BinaryData False (ASCII samples) is not supported");
    const std::string* typeName = field(header, "elementtype");
    if (!typeName) throwInputError(path, "missing ElementType");
    const ScalarType type = metaType(path, *typeName);
    const std::string* dimSize = field(header, "dimsize");
    if (!dimSize) throwInputError(path, "missing DimSize");
    const std::vector<long long> dims = parseIntegers(path, "DimSize", *dimSize, 3);
    const CheckedShape shape = checkShape(path, {dims[0], dims[1], dims[2]}, type);
    const bool bigEndian = booleanField(path, header, "elementbyteordermsb") ||
                           booleanField(path, header, "binarydatabyteordermsb") ||
                           booleanField(path, header, "byteordermsb");

    MetaFile file;
    file.shape = shape;
    file.format.type = type;
    file.format.bigEndian = bigEndian;
    Volume& volume = file.format.grid;
    volume.dims = shape.dims;
    volume.spacing = spacingOf(path, header);
    volume.origin = originOf(path, header);
    if (const auto axes = axesOf(path, header)) {
        volume.patientAxes = *axes;
        volume.orientationKnown = true;
    }
    volume.sourceType = type;
    volume.name = fileStem(path);
    file.payload = locatePayload(path, header, shape.bytes);
    return file;
}

StoredSamples storedSamplesOf(MetaFile file) {
    return {std::move(file.format), {{file.payload.file, file.payload.start, file.shape.bytes}}};
}

// A compressed payload as one zlib stream of CompressedDataSize bytes (or to the file's end).
GzipSamples gzipSamplesOf(MetaFile file) {
    return {std::move(file.format),
            {{file.payload.file, file.payload.start, 0, file.shape.bytes, file.payload.packedSize}}};
}

} // namespace

std::optional<StoredSamples> detail::storedMetaImageSamples(const std::string& path) {
    MetaFile file = openMetaImage(path);
    if (file.payload.compressed) return std::nullopt;
    return storedSamplesOf(std::move(file));
}

std::optional<GzipSamples> detail::gzipMetaImageSamples(const std::string& path) {
    MetaFile file = openMetaImage(path);
    if (!file.payload.compressed) return std::nullopt;
    return gzipSamplesOf(std::move(file));
}

Volume loadMetaImage(const std::string& path, SampleStorage storage) {
    MetaFile file = openMetaImage(path);
    if (!file.payload.compressed) return readStoredVolume(path, storedSamplesOf(std::move(file)), storage);
    // The same stream reader as a rank's planes, over every plane: streamed, never held compressed.
    return readGzipVolume(path, gzipSamplesOf(std::move(file)), storage);
}

} // namespace vots::fit
