// Private file access for the volume readers: size checks, exact reads and one-line InputError messages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// Throws InputError("<path>: <problem>"), the one message shape of every reader.
[[noreturn]] void throwInputError(const std::string& path, const std::string& problem);

/// Size of a regular file; throws for a missing path, a folder or any other non-file.
std::uint64_t regularFileSize(const std::string& path);

/// Throws (naming the shortfall) unless the file holds `count` bytes from `offset`.
void checkFileHolds(const std::string& path, std::uint64_t offset, std::size_t count);

/// Exactly `count` bytes starting at `offset`; throws when the file is shorter.
std::vector<unsigned char> readFileBytes(const std::string& path, std::uint64_t offset, std::size_t count);

/// The same bytes written at `destination` (which holds at least `count`), so they land where they stay.
void readFileBytesInto(const std::string& path, std::uint64_t offset, std::size_t count,
                       unsigned char* destination);

/// The first min(file size, maxBytes) bytes, for header parsing.
std::string readFilePrefix(const std::string& path, std::size_t maxBytes);

/// Offset just past `lines` further newlines from `offset`; throws when the file ends first.
std::uint64_t skipLines(const std::string& path, std::uint64_t offset, long long lines);

/// "dir/neghip.nrrd" -> "neghip", "a/b.nii.gz" -> "b".
std::string fileStem(const std::string& path);

/// A data file named in a header: absolute names stay, relative ones are taken from the header's folder.
std::string pathBesideHeader(const std::string& headerPath, const std::string& name);

/// Lower-case extension including the dot; ".nii.gz" counts as one extension.
std::string volumeExtension(const std::string& path);

/// Throws the one error of a frame outside [0, frames) of a 4D file, naming the frames it holds.
void checkFrame(const std::string& path, int frame, std::uint64_t frames);

/// Throws loadVolume's error for a path that is neither a known format nor a DICOM folder.
[[noreturn]] void throwUnknownVolumeFormat(const std::string& path);

} // namespace vots::fit::detail
