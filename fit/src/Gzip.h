// Private: zlib inflation of gzip or zlib streams with exact, checked sizes; no decompressor of our own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// Streams a gzip (also multi-member) or zlib stream, detected from its header. Output memory grows
/// with the data actually decompressed, so a header claiming a huge size costs nothing up front.
class Inflater {
public:
    /// `path` only names the file in error messages; `data` must outlive the Inflater.
    Inflater(std::string path, const unsigned char* data, std::size_t size);
    /// The stream in `file` from byte `offset` to its end (or over `length` bytes, when given), read a
    /// chunk at a time (never held whole), so a reader that stops early has read only the compressed
    /// bytes up to its data.
    Inflater(std::string path, const std::string& file, std::uint64_t offset,
             std::optional<std::uint64_t> length = std::nullopt);
    ~Inflater();
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    /// Exactly `count` decompressed bytes; throws InputError when the stream ends first or is corrupt.
    std::vector<unsigned char> readExactly(std::size_t count);
    /// Exactly `count` decompressed bytes at `destination` (memory the caller already holds); throws as
    /// readExactly.
    void readInto(unsigned char* destination, std::size_t count);
    /// Discards exactly `count` bytes.
    void skip(std::size_t count);
    /// Throws InputError unless the stream ends here (checking its CRC on the way).
    void expectEnd();

private:
    std::size_t read(unsigned char* out, std::size_t count);
    /// Hands zlib at least `want` bytes of input where that much is left (fewer only at the end).
    void topUp(std::size_t want);
    /// True when the input left after a stream's end is zeros only (padding); consumes it.
    bool restIsZeros();

    struct State;
    std::string mPath;
    std::unique_ptr<State> mState;
    std::size_t mProduced = 0; // bytes handed out so far, for messages
};

/// Inflates a whole stream that must hold exactly `expected` bytes.
std::vector<unsigned char> inflateExact(const std::string& path, const unsigned char* data, std::size_t size,
                                        std::size_t expected);

/// True when the bytes start with the gzip magic 1f 8b.
bool hasGzipMagic(const unsigned char* data, std::size_t size);

/// True when the file starts with the gzip magic (a .nii.gz, .mgz); throws for a missing file.
bool isGzipFile(const std::string& path);

} // namespace vots::fit::detail
