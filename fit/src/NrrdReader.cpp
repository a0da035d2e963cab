// Reads NRRD volumes: attached (.nrrd) or detached (.nhdr) headers, raw or gzip encoding, 3D scalars only.
#include "vots/fit/VolumeLoad.h"

#include "vots/fit/Error.h"
#include "vots/fit/PatientAxes.h"

#include "GzipPlanes.h"
#include "HeaderText.h"
#include "InputFile.h"
#include "SampleDecode.h"
#include "StoredSamples.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

namespace vots::fit {

namespace {

using namespace detail;

constexpr std::size_t MAX_HEADER_BYTES = std::size_t{1} << 20;
constexpr long long MAX_DATA_FILES = 100000;

struct NrrdHeader {
    std::string type, sizes, spacings, space, directions, origin, endian, encoding, dataFile;
    long long dimension = 0;
    long long lineSkip = 0;
    long long byteSkip = 0;
    std::vector<std::string> listedFiles;    // the names after "data file: LIST"
    std::optional<std::uint64_t> dataOffset; // attached data starts here, just past the blank line
};

// Field names have old spellings without blanks ("datafile", "lineskip").
std::string canonicalKey(const std::string& key) {
    const std::string lower = toLower(trim(key));
    if (lower == "datafile") return "data file";
    if (lower == "lineskip") return "line skip";
    if (lower == "byteskip") return "byte skip";
    return lower;
}

long long integerField(const std::string& path, const std::string& key, const std::string& value) {
    return parseIntegers(path, key, value, 1)[0];
}

NrrdHeader parseHeader(const std::string& path, const std::string& text, std::uint64_t fileSize) {
    if (text.size() < 8 || text.compare(0, 7, "NRRD000") != 0)
        throwInputError(path, "not a NRRD file (it does not start with NRRD000x)");
    NrrdHeader header;
    HeaderLine line = lineAt(text, 0);
    bool inList = false;
    while (line.next < text.size()) {
        line = lineAt(text, line.next);
        if (!line.complete && text.size() < fileSize)
            throwInputError(path, "header is longer than " + std::to_string(MAX_HEADER_BYTES) + " bytes");
        if (line.text.empty()) {
            header.dataOffset = line.next;
            break;
        }
        if (inList) {
            header.listedFiles.push_back(trim(line.text));
            continue;
        }
        if (line.text.front() == '#' || line.text.find(":=") != std::string::npos)
            continue; // comment, key/value
        const std::size_t colon = line.text.find(':');
        if (colon == std::string::npos)
            throwInputError(path, "bad header line '" + quotable(line.text) + "'");
        const std::string key = canonicalKey(line.text.substr(0, colon));
        const std::string value = trim(line.text.substr(colon + 1));
        if (key == "type")
            header.type = value;
        else if (key == "dimension")
            header.dimension = integerField(path, key, value);
        else if (key == "sizes")
            header.sizes = value;
        else if (key == "spacings")
            header.spacings = value;
        else if (key == "space")
            header.space = toLower(value);
        else if (key == "space directions")
            header.directions = value;
        else if (key == "space origin")
            header.origin = value;
        else if (key == "endian")
            header.endian = toLower(value);
        else if (key == "encoding")
            header.encoding = toLower(value);
        else if (key == "line skip")
            header.lineSkip = integerField(path, key, value);
        else if (key == "byte skip")
            header.byteSkip = integerField(path, key, value);
        else if (key == "data file") {
            header.dataFile = value;
            const std::vector<std::string> words = splitWords(value);
            inList = !words.empty() && words[0] == "LIST";
        }
        // Other fields (kinds, centers, units, content, ...) do not change the samples.
    }
    return header;
}

// "(1,0,0) (0,1.5,0) none" -> one vector per entry; "none" gives an empty vector.
std::vector<std::vector<double>> parseVectors(const std::string& path, const std::string& field,
                                              const std::string& value) {
    std::vector<std::vector<double>> vectors;
    std::size_t i = 0;
    while (i < value.size()) {
        if (value[i] == ' ' || value[i] == '\t') {
            ++i;
        } else if (value[i] == '(') {
            const std::size_t close = value.find(')', i);
            if (close == std::string::npos) throwInputError(path, "'" + field + "' has an unclosed '('");
            std::string inner = value.substr(i + 1, close - i - 1);
            for (char& c : inner)
                if (c == ',') c = ' ';
            const std::vector<std::string> words = splitWords(inner);
            vectors.push_back(parseReals(path, field, inner, words.size()));
            i = close + 1;
        } else if (value.compare(i, 4, "none") == 0) {
            vectors.emplace_back();
            i += 4;
        } else {
            throwInputError(path,
                            "'" + field + "' is not a list of (x,y,z) vectors: '" + quotable(value) + "'");
        }
    }
    return vectors;
}

std::array<double, 3> readSpacing(const std::string& path, const NrrdHeader& header) {
    std::array<double, 3> spacing{1.0, 1.0, 1.0};
    if (!header.directions.empty()) {
        const auto vectors = parseVectors(path, "space directions", header.directions);
        if (vectors.size() != 3) throwInputError(path, "'space directions' needs 3 vectors");
        for (int a = 0; a < 3; ++a) {
            if (vectors[a].empty()) throwInputError(path, "'space directions' has 'none' for a spatial axis");
            double squares = 0.0;
            for (const double v : vectors[a])
                squares += v * v;
            spacing[a] = checkedSpacing(path, "space directions", std::sqrt(squares));
        }
    } else if (!header.spacings.empty()) {
        const std::vector<double> values = parseReals(path, "spacings", header.spacings, 3);
        for (int a = 0; a < 3; ++a) // NRRD writes "nan" for an axis without spacing
            spacing[a] = std::isnan(values[a]) ? 1.0 : checkedSpacing(path, "spacings", values[a]);
    }
    return spacing;
}

std::array<double, 3> readOrigin(const std::string& path, const NrrdHeader& header) {
    std::array<double, 3> origin{0.0, 0.0, 0.0};
    if (header.origin.empty()) return origin;
    const auto vectors = parseVectors(path, "space origin", header.origin);
    if (vectors.size() != 1 || vectors[0].size() != 3)
        throwInputError(path, "'space origin' must be one (x,y,z)");
    for (int a = 0; a < 3; ++a) {
        if (!std::isfinite(vectors[0][a])) throwInputError(path, "'space origin' is not finite");
        origin[a] = vectors[0][a];
    }
    return origin;
}

// The sign that turns each coordinate of the header's patient space into LPS; nullopt for a space
// without patient meaning (scanner-xyz, 3D-right-handed, 3D-left-handed) or none given.
std::optional<std::array<double, 3>> lpsSigns(const std::string& path, const std::string& space) {
    if (space == "left-posterior-superior" || space == "lps") return std::array<double, 3>{1.0, 1.0, 1.0};
    if (space == "right-anterior-superior" || space == "ras") return std::array<double, 3>{-1.0, -1.0, 1.0};
    if (space == "left-anterior-superior" || space == "las") return std::array<double, 3>{1.0, -1.0, 1.0};
    if (space.find("time") != std::string::npos || space == "rast" || space == "last" || space == "lpst")
        throwInputError(path,
                        "space '" + quotable(space) + "' has a time axis; only 3D volumes are supported");
    return std::nullopt;
}

// Patient axes from `space` and `space directions`, and the origin turned into LPS with them. A header
// with spacings only, or a space without patient meaning, leaves the volume in index space.
void readOrientation(const std::string& path, const NrrdHeader& header, Volume& volume) {
    const auto signs = lpsSigns(path, header.space);
    if (!signs || header.directions.empty()) return;
    const auto vectors = parseVectors(path, "space directions", header.directions);
    PatientAxes directions{};
    for (std::size_t a = 0; a < 3; ++a) {
        if (vectors[a].size() != 3) throwInputError(path, "'space directions' vectors must be (x,y,z)");
        for (std::size_t c = 0; c < 3; ++c)
            directions[a][c] = (*signs)[c] * vectors[a][c];
    }
    const auto axes = normalizedPatientAxes(directions);
    if (!axes) throwInputError(path, "'space directions' do not span space");
    volume.patientAxes = *axes;
    volume.orientationKnown = true;
    for (std::size_t c = 0; c < 3; ++c)
        volume.origin[c] = volume.origin[c] == 0.0 ? 0.0 : (*signs)[c] * volume.origin[c];
}

// "slice%03d.raw 1 93 1 [subdim]" -> slice001.raw ... slice093.raw. Only %d with an optional
// zero flag and width is accepted, so a hostile format string is never handed to printf.
std::vector<std::string> expandPattern(const std::string& path, const std::vector<std::string>& words) {
    const std::string& format = words[0];
    const std::size_t percent = format.find('%');
    std::size_t i = percent + 1;
    const bool zeroPad = i < format.size() && format[i] == '0';
    std::size_t width = 0;
    while (i < format.size() && format[i] >= '0' && format[i] <= '9' && width < 100)
        width = width * 10 + static_cast<std::size_t>(format[i++] - '0');
    if (i >= format.size() || format[i] != 'd' || format.find('%', i) != std::string::npos)
        throwInputError(path, "'data file' pattern '" + quotable(format) + "' must contain exactly one %d");
    const std::string prefix = format.substr(0, percent);
    const std::string suffix = format.substr(i + 1);
    const auto first = parseInteger(words[1]);
    const auto last = parseInteger(words[2]);
    const auto step = parseInteger(words[3]);
    // Unsigned arithmetic: last - first and first + k * step overflow long long for extreme values.
    using U = unsigned long long;
    const bool up = step && *step > 0;
    const bool ordered = first && last && step && *step != 0 && (up ? *last >= *first : *last <= *first);
    const U span = !ordered ? 0 : up ? U(*last) - U(*first) : U(*first) - U(*last);
    const U stride = !ordered ? 1 : up ? U(*step) : U(0) - U(*step);
    if (!ordered || span / stride >= static_cast<U>(MAX_DATA_FILES))
        throwInputError(path, "'data file' pattern needs <min> <max> <step> describing 1 to " +
                                  std::to_string(MAX_DATA_FILES) + " files");
    std::vector<std::string> names;
    for (U k = 0; k <= span / stride; ++k) {
        const long long n = static_cast<long long>(up ? U(*first) + k * stride : U(*first) - k * stride);
        std::string number = std::to_string(n);
        if (number.size() < width) // printf pads zeros after the sign, blanks before it
            number.insert(zeroPad && n < 0 ? 1 : 0, width - number.size(), zeroPad ? '0' : ' ');
        names.push_back(prefix + number + suffix);
    }
    return names;
}

// The files holding the samples and where each one's data starts.
std::vector<std::pair<std::string, std::uint64_t>> dataSources(const std::string& path,
                                                               const NrrdHeader& header) {
    std::vector<std::pair<std::string, std::uint64_t>> sources;
    if (header.dataFile.empty()) {
        if (!header.dataOffset)
            throwInputError(path,
                            "no data: neither a blank line before attached data nor a 'data file' field");
        sources.emplace_back(path, *header.dataOffset);
        return sources;
    }
    const std::vector<std::string> words = splitWords(header.dataFile);
    std::vector<std::string> names;
    if (words[0] == "LIST")
        names = header.listedFiles;
    else if (words.size() >= 4 && words[0].find('%') != std::string::npos)
        names = expandPattern(path, words);
    else
        names.push_back(header.dataFile);
    if (names.empty()) throwInputError(path, "'data file: LIST' names no files");
    for (const std::string& name : names) {
        const std::string file = pathBesideHeader(path, name);
        try {
            regularFileSize(file);
        } catch (const InputError& error) {
            throwInputError(path, "data file '" + name + "' cannot be used (" + error.what() + ")");
        }
        sources.emplace_back(file, 0);
    }
    return sources;
}

// Where one raw data file's share of the payload (`bytes` long) starts; throws unless the file holds
// exactly that share from there.
std::uint64_t rawDataStart(const NrrdHeader& header, const std::string& file, std::uint64_t offset,
                           std::size_t bytes) {
    const std::uint64_t size = regularFileSize(file);
    if (header.lineSkip > 0) offset = skipLines(file, offset, header.lineSkip);
    // byte skip -1: the samples are the last bytes of the file, whatever precedes them.
    const std::uint64_t start = header.byteSkip < 0 ? (size >= bytes ? size - bytes : 0)
                                                    : offset + static_cast<std::uint64_t>(header.byteSkip);
    const std::uint64_t have = size > start ? size - start : 0;
    if (have > bytes)
        throwInputError(file, "holds " + std::to_string(have) + " data bytes but the header describes " +
                                  std::to_string(bytes) + " (wrong sizes or type?)");
    if (have < bytes) // the message readFileBytes gives for a short file
        throwInputError(file, "truncated: needs " + std::to_string(bytes) + " bytes from byte " +
                                  std::to_string(start) + ", file has only " + std::to_string(have));
    return start;
}

// A NRRD file whose header passed every check: its grid, sample layout and data files.
struct NrrdFile {
    NrrdHeader header;
    SampleFormat format; // the grid has no samples yet
    CheckedShape shape;
    bool gzip = false;
    std::vector<std::pair<std::string, std::uint64_t>> sources; // each data file and where its data starts
    std::size_t perFile = 0;                                    // payload bytes in each data file
};

NrrdFile openNrrd(const std::string& path) {
    const std::uint64_t fileSize = regularFileSize(path);
    const std::string text = readFilePrefix(path, MAX_HEADER_BYTES);
    NrrdFile file;
    file.header = parseHeader(path, text, fileSize);
    const NrrdHeader& header = file.header;

    if (header.dimension != 3)
        throwInputError(path, "dimension is " + std::to_string(header.dimension) +
                                  "; only 3D volumes are supported");
    if (header.type.empty()) throwInputError(path, "missing 'type' field");
    const std::optional<ScalarType> type = findScalarType(header.type);
    if (!type)
        throwInputError(path, "unsupported type '" + quotable(header.type) +
                                  "' (supported: int8, uint8, int16, uint16, int32, uint32, float, double)");
    if (header.sizes.empty()) throwInputError(path, "missing 'sizes' field");
    const std::vector<long long> sizes = parseIntegers(path, "sizes", header.sizes, 3);
    file.shape = checkShape(path, {sizes[0], sizes[1], sizes[2]}, *type);

    file.gzip = header.encoding == "gzip" || header.encoding == "gz";
    if (!file.gzip && header.encoding != "raw")
        throwInputError(path, header.encoding.empty() ? "missing 'encoding' field"
                                                      : "unsupported encoding '" + quotable(header.encoding) +
                                                            "' (supported: raw, gzip)");
    if (scalarTypeSize(*type) > 1 && header.endian != "little" && header.endian != "big")
        throwInputError(path, header.endian.empty() ? "missing 'endian' field for a multi-byte type"
                                                    : "bad 'endian' value '" + quotable(header.endian) + "'");
    if (header.lineSkip < 0) throwInputError(path, "'line skip' is negative");
    if (header.byteSkip < -1) throwInputError(path, "'byte skip' must be -1 or at least 0");

    Volume& volume = file.format.grid;
    volume.dims = file.shape.dims;
    volume.spacing = readSpacing(path, header);
    volume.origin = readOrigin(path, header);
    readOrientation(path, header, volume);
    volume.sourceType = *type;
    volume.name = fileStem(path);
    file.format.type = *type;
    file.format.bigEndian = header.endian == "big";

    file.sources = dataSources(path, header);
    if (file.shape.bytes % file.sources.size() != 0)
        throwInputError(path, std::to_string(file.sources.size()) + " data files cannot split " +
                                  std::to_string(file.shape.bytes) + " bytes evenly");
    file.perFile = file.shape.bytes / file.sources.size();
    return file;
}

// The raw payload's place in the data files.
StoredSamples storedSamplesOf(NrrdFile file) {
    StoredSamples stored{std::move(file.format), {}};
    // Every file's size is checked before the samples' memory is taken.
    for (const auto& [name, offset] : file.sources)
        stored.pieces.push_back({name, rawDataStart(file.header, name, offset, file.perFile), file.perFile});
    return stored;
}

// The gzip streams in the data files: each starts after the file's line skip; the byte skip counts
// decompressed bytes.
GzipSamples gzipSamplesOf(NrrdFile file) {
    GzipSamples stored{std::move(file.format), {}};
    for (const auto& [name, offset] : file.sources) {
        if (file.header.byteSkip < 0)
            throwInputError(name, "'byte skip: -1' cannot be used with gzip encoding");
        const std::uint64_t start =
            file.header.lineSkip > 0 ? skipLines(name, offset, file.header.lineSkip) : offset;
        stored.pieces.push_back(
            {name, start, static_cast<std::uint64_t>(file.header.byteSkip), file.perFile, std::nullopt});
    }
    return stored;
}

} // namespace

std::optional<StoredSamples> detail::storedNrrdSamples(const std::string& path) {
    NrrdFile file = openNrrd(path);
    if (file.gzip) return std::nullopt;
    return storedSamplesOf(std::move(file));
}

std::optional<GzipSamples> detail::gzipNrrdSamples(const std::string& path) {
    NrrdFile file = openNrrd(path);
    if (!file.gzip) return std::nullopt;
    return gzipSamplesOf(std::move(file));
}

Volume loadNrrd(const std::string& path, SampleStorage storage) {
    NrrdFile file = openNrrd(path);
    if (!file.gzip) return readStoredVolume(path, storedSamplesOf(std::move(file)), storage);
    return readGzipVolume(path, gzipSamplesOf(std::move(file)), storage);
}

} // namespace vots::fit
