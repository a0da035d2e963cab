// Private: zlib inflation of gzip or zlib streams with exact, checked sizes; no decompressor of our own.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace vots::fit::detail {

/// Streams a gzip (also multi-member) or zlib stream, detected from its header. Output memory grows
/// with the data actually decompressed, so a header claiming a huge size costs nothing up front.
class Inflater {
public:
    /// `path` only names the file in error messages; `data` must outlive the Inflater.
    Inflater(std::string path, const unsigned char* data, std::size_t size);
    ~Inflater();
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    /// Exactly `count` decompressed bytes; throws InputError when the stream ends first or is corrupt.
    std::vector<unsigned char> readExactly(std::size_t count);
    /// Discards exactly `count` bytes.
    void skip(std::size_t count);
    /// Throws InputError unless the stream ends here (checking its CRC on the way).
    void expectEnd();

private:
    std::size_t read(unsigned char* out, std::size_t count);

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

} // namespace vots::fit::detail
