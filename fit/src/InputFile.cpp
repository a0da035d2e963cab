// Private file access for the volume readers: size checks, exact reads and one-line InputError messages.
#include "InputFile.h"

#include "vots/fit/Error.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace vots::fit::detail {

namespace fs = std::filesystem;

void throwInputError(const std::string& path, const std::string& problem) {
    throw InputError(path + ": " + problem);
}

std::uint64_t regularFileSize(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
        throwInputError(path, "cannot access the file (" + ec.message() + ")");
    if (!fs::exists(status)) throwInputError(path, "no such file");
    if (fs::is_directory(status)) throwInputError(path, "is a folder, not a volume file");
    if (!fs::is_regular_file(status)) throwInputError(path, "is not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throwInputError(path, "cannot read the file size (" + ec.message() + ")");
    return size;
}

namespace {

std::ifstream openAt(const std::string& path, std::uint64_t offset) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throwInputError(path, "cannot open the file for reading");
    in.seekg(static_cast<std::streamoff>(offset));
    if (!in) throwInputError(path, "cannot seek to byte " + std::to_string(offset));
    return in;
}

} // namespace

void checkFileHolds(const std::string& path, std::uint64_t offset, std::size_t count) {
    const std::uint64_t size = regularFileSize(path);
    if (offset > size || size - offset < count) {
        const std::uint64_t have = offset > size ? 0 : size - offset;
        throwInputError(path, "truncated: needs " + std::to_string(count) + " bytes from byte " +
                                  std::to_string(offset) + ", file has only " + std::to_string(have));
    }
}

void readFileBytesInto(const std::string& path, std::uint64_t offset, std::size_t count,
                       unsigned char* destination) {
    checkFileHolds(path, offset, count);
    std::ifstream in = openAt(path, offset);
    in.read(reinterpret_cast<char*>(destination), static_cast<std::streamsize>(count));
    if (static_cast<std::size_t>(in.gcount()) != count) throwInputError(path, "read error (file changed?)");
}

std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t offset, std::size_t count) {
    // Check the size first, so a header that claims gigabytes costs nothing before it is caught.
    checkFileHolds(path, offset, count);
    std::vector<unsigned char> bytes(count);
    readFileBytesInto(path, offset, count, bytes.data());
    return bytes;
}

std::string readFilePrefix(const std::string& path, std::size_t maxBytes) {
    const std::uint64_t size = regularFileSize(path);
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(size, maxBytes));
    std::string text(count, '\0');
    std::ifstream in = openAt(path, 0);
    in.read(text.data(), static_cast<std::streamsize>(count));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

std::uint64_t skipLines(const std::string& path, std::uint64_t offset, long long lines) {
    std::ifstream in = openAt(path, offset);
    std::uint64_t pos = offset;
    std::vector<char> chunk(1 << 16);
    while (lines > 0) {
        in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) throwInputError(path, "ends before the " + std::to_string(lines) + " lines to skip");
        std::size_t i = 0;
        for (; i < got && lines > 0; ++i)
            if (chunk[i] == '\n') --lines;
        pos += i;
    }
    return pos;
}

std::string fileStem(const std::string& path) {
    std::string name = fs::path(path).filename().string();
    std::string lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (lower.size() > 3 && lower.ends_with(".gz")) name.resize(name.size() - 3);
    const std::size_t dot = name.rfind('.');
    if (dot != std::string::npos && dot > 0) name.resize(dot);
    return name;
}

std::string pathBesideHeader(const std::string& headerPath, const std::string& name) {
    const fs::path data(name);
    if (data.is_absolute()) return name;
    return (fs::path(headerPath).parent_path() / data).string();
}

std::string volumeExtension(const std::string& path) {
    std::string name = fs::path(path).filename().string();
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    if (name.ends_with(".nii.gz")) return ".nii.gz";
    const std::size_t dot = name.rfind('.');
    return dot == std::string::npos ? std::string() : name.substr(dot);
}

void checkFrame(const std::string& path, int frame, std::uint64_t frames) {
    if (frame < 0 || static_cast<std::uint64_t>(frame) >= frames)
        throwInputError(
            path, "has no frame " + std::to_string(frame) + ": it holds " + std::to_string(frames) +
                      (frames == 1 ? " frame (0)" : " frames (0 to " + std::to_string(frames - 1) + ")"));
}

void throwUnknownVolumeFormat(const std::string& path) {
    // Existence first: "no such file" is the more useful message for a mistyped path.
    regularFileSize(path);
    throwInputError(path, "unknown volume format '" + volumeExtension(path) +
                              "' (expected .nrrd, .nhdr, .nii, .nii.gz, .mgh, .mgz, .mhd, .mha, a DICOM "
                              "folder, or a raw layout)");
}

} // namespace vots::fit::detail
