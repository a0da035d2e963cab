// Private: zlib inflation of gzip or zlib streams with exact, checked sizes; no decompressor of our own.
#include "Gzip.h"

#include "InputFile.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <utility>
#include <zlib.h>

namespace vots::fit::detail {

namespace {
constexpr std::size_t MAX_CHUNK = UINT_MAX; // zlib counts in uInt
constexpr std::size_t FIRST_ALLOCATION = std::size_t{1} << 20;
constexpr std::size_t FILE_CHUNK = std::size_t{1} << 20; // compressed bytes read from a file at a time
} // namespace

struct Inflater::State {
    z_stream stream{};
    // In memory: the input not yet handed to zlib, right after stream.next_in + stream.avail_in.
    const unsigned char* next = nullptr;
    std::size_t left = 0;
    // In a file: the bytes not yet read, and the buffer zlib reads them from.
    bool fromFile = false;
    std::string file;
    std::uint64_t fileNext = 0;
    std::uint64_t fileLeft = 0;
    std::vector<unsigned char> buffer;
    bool ended = false;
    std::uint64_t notHandedOver() const { return fromFile ? fileLeft : left; }
};

bool isGzipFile(const std::string& path) {
    const std::uint64_t fileSize = regularFileSize(path);
    const std::vector<unsigned char> magic = readFileBytes(path, 0, fileSize < 2 ? 0 : 2);
    return hasGzipMagic(magic.data(), magic.size());
}

bool hasGzipMagic(const unsigned char* data, std::size_t size) {
    return size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
}

Inflater::Inflater(std::string path, const unsigned char* data, std::size_t size)
    : mPath(std::move(path)), mState(std::make_unique<State>()) {
    mState->next = data;
    mState->left = size;
    // 15 + 32: window of 32 KiB, and let zlib detect a gzip or zlib header by itself.
    if (inflateInit2(&mState->stream, 15 + 32) != Z_OK) throwInputError(mPath, "cannot start zlib inflate");
}

Inflater::Inflater(std::string path, const std::string& file, std::uint64_t offset,
                   std::optional<std::uint64_t> length)
    : mPath(std::move(path)), mState(std::make_unique<State>()) {
    State& s = *mState;
    s.fromFile = true;
    s.file = file;
    const std::uint64_t size = regularFileSize(file);
    s.fileNext = offset;
    s.fileLeft = size > offset ? size - offset : 0;
    if (length) s.fileLeft = std::min(s.fileLeft, *length);
    if (inflateInit2(&s.stream, 15 + 32) != Z_OK) throwInputError(mPath, "cannot start zlib inflate");
}

Inflater::~Inflater() {
    inflateEnd(&mState->stream);
}

std::size_t Inflater::read(unsigned char* out, std::size_t count) {
    State& s = *mState;
    std::size_t done = 0;
    while (done < count && !s.ended) {
        if (s.stream.avail_in == 0) topUp(1);
        const std::size_t room = std::min(count - done, MAX_CHUNK);
        s.stream.next_out = out + done;
        s.stream.avail_out = static_cast<uInt>(room);
        const int rc = inflate(&s.stream, Z_NO_FLUSH);
        done += room - s.stream.avail_out;
        if (rc == Z_STREAM_END) {
            // Another gzip member may follow (as `cat a.gz b.gz` makes); zero padding is tolerated.
            const std::uint64_t rest = s.stream.avail_in + s.notHandedOver();
            topUp(2); // a member's magic may lie across two chunks of a file
            if (s.stream.avail_in >= 2 && hasGzipMagic(s.stream.next_in, s.stream.avail_in)) {
                inflateReset(&s.stream);
                continue;
            }
            if (!restIsZeros())
                throwInputError(mPath,
                                "unexpected " + std::to_string(rest) + " bytes after the compressed stream");
            s.ended = true;
        } else if (rc == Z_BUF_ERROR || (rc == Z_OK && s.stream.avail_in == 0 && s.notHandedOver() == 0 &&
                                         s.stream.avail_out > 0)) {
            if (s.stream.avail_in == 0 && s.notHandedOver() == 0)
                throwInputError(mPath, "compressed data is truncated (stream ends after " +
                                           std::to_string(mProduced + done) + " decompressed bytes)");
        } else if (rc != Z_OK) {
            const std::string why = s.stream.msg ? s.stream.msg : "error " + std::to_string(rc);
            throwInputError(mPath, "corrupt compressed data (zlib: " + why + ")");
        }
    }
    mProduced += done;
    return done;
}

void Inflater::topUp(std::size_t want) {
    State& s = *mState;
    if (s.stream.avail_in >= want || s.notHandedOver() == 0) return;
    if (!s.fromFile) {
        // The input is one block: the bytes not yet handed over follow those zlib still has.
        if (s.stream.avail_in == 0)
            s.stream.next_in = const_cast<unsigned char*>(s.next); // not const-correct
        const std::size_t take = std::min(s.left, MAX_CHUNK - s.stream.avail_in);
        s.stream.avail_in += static_cast<uInt>(take);
        s.next += take;
        s.left -= take;
        return;
    }
    // The bytes zlib has not taken move to the buffer's start, the file's next bytes follow them.
    if (s.buffer.empty()) s.buffer.resize(FILE_CHUNK);
    const std::size_t kept = s.stream.avail_in;
    if (kept > 0) std::memmove(s.buffer.data(), s.stream.next_in, kept);
    const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(s.fileLeft, FILE_CHUNK - kept));
    readFileBytesInto(s.file, s.fileNext, take, s.buffer.data() + kept);
    s.fileNext += take;
    s.fileLeft -= take;
    s.stream.next_in = s.buffer.data();
    s.stream.avail_in = static_cast<uInt>(kept + take);
}

bool Inflater::restIsZeros() {
    State& s = *mState;
    while (true) {
        const unsigned char* tail = s.stream.next_in;
        if (!std::all_of(tail, tail + s.stream.avail_in, [](unsigned char c) { return c == 0; }))
            return false;
        s.stream.next_in += s.stream.avail_in;
        s.stream.avail_in = 0;
        if (s.notHandedOver() == 0) return true;
        topUp(1);
    }
}

void Inflater::readInto(unsigned char* destination, std::size_t count) {
    const std::size_t got = read(destination, count);
    if (got < count)
        throwInputError(mPath, "decompressed data is too short: " + std::to_string(mProduced) +
                                   " bytes in all, needed " + std::to_string(mProduced - got + count));
}

std::vector<unsigned char> Inflater::readExactly(std::size_t count) {
    std::vector<unsigned char> out;
    std::size_t have = 0;
    while (have < count) {
        // Grow by doubling, so memory follows real data rather than the header's claim.
        const std::size_t target = std::min(count, std::max(FIRST_ALLOCATION, have * 2));
        out.resize(target);
        const std::size_t got = read(out.data() + have, target - have);
        have += got;
        if (have < target) break;
    }
    if (have < count)
        throwInputError(mPath, "decompressed data is too short: " + std::to_string(mProduced) +
                                   " bytes in all, needed " + std::to_string(mProduced - have + count));
    return out;
}

void Inflater::skip(std::size_t count) {
    std::vector<unsigned char> scratch(std::min<std::size_t>(count, 1 << 16));
    std::size_t left = count;
    while (left > 0) {
        const std::size_t want = std::min(left, scratch.size());
        if (read(scratch.data(), want) < want)
            throwInputError(mPath, "decompressed data ends after " + std::to_string(mProduced) +
                                       " bytes, before the data starts");
        left -= want;
    }
}

void Inflater::expectEnd() {
    unsigned char extra = 0;
    if (read(&extra, 1) != 0)
        throwInputError(mPath, "decompressed data is longer than the header says (" +
                                   std::to_string(mProduced - 1) + " bytes expected)");
}

std::vector<unsigned char> inflateExact(const std::string& path, const unsigned char* data, std::size_t size,
                                        std::size_t expected) {
    Inflater inflater(path, data, size);
    std::vector<unsigned char> out = inflater.readExactly(expected);
    inflater.expectEnd();
    return out;
}

} // namespace vots::fit::detail
