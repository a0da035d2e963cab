// Vot-Space file v1 (docs/DESIGN.md §8): explicit little-endian packing and full validation; no file I/O.
#include "vots/fit/VotSpaceFile.h"

#include "vots/fit/Volume.h"

#include "vots/fit/Error.h"

#include "Crc32.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace vots::fit {
namespace {

// Header field offsets (docs/DESIGN.md §8). Everything is little-endian, whatever the host.
constexpr std::size_t OFF_MAGIC = 0;        // 4B "VOTS"
constexpr std::size_t OFF_VERSION = 4;      // u32
constexpr std::size_t OFF_HEADER_BYTES = 8; // u32 = 128
constexpr std::size_t OFF_DIMS = 12;        // u32[3], grid points along x, y, z
constexpr std::size_t OFF_ORIGIN = 24;      // f64[3], world position of grid point (0,0,0)
constexpr std::size_t OFF_SPACING = 48;     // f64[3], world distance between grid points
constexpr std::size_t OFF_DEGREE = 72;      // u32, 0..3
constexpr std::size_t OFF_EPS = 76;         // f32, context eps, data units
constexpr std::size_t OFF_BACKGROUND = 80;  // f32, data units
constexpr std::size_t OFF_FLAGS = 84;       // u32, bit 0: eps varies in space
constexpr std::size_t OFF_VOT_COUNT = 88;   // u64
constexpr std::size_t OFF_META_BYTES = 96;  // u64
constexpr std::size_t OFF_RESERVED = 104;   // 24B, zero
constexpr std::size_t CRC_BYTES = 4;        // u32 CRC-32 (zlib) of every preceding byte

// Record field offsets, relative to the record start (120 bytes per Vot).
constexpr std::size_t REC_LO = 0;   // i32[3], box lo, grid index space
constexpr std::size_t REC_HI = 12;  // i32[3], box hi, inclusive
constexpr std::size_t REC_P = 24;   // f32[3], expansion point, grid index space
constexpr std::size_t REC_ERR = 36; // f32, max |residual| at the box's grid samples
constexpr std::size_t REC_C = 40;   // f32[20], Taylor coefficients, canonical order (docs/DESIGN.md §1)

constexpr std::uint32_t KNOWN_FLAGS = VotSpace::FLAG_EPS_VARIES;

static_assert(OFF_RESERVED + 24 == VOTS_HEADER_BYTES);
static_assert(REC_C + 4 * MONOMIAL_COUNT == VOTS_RECORD_BYTES);

void putU32(std::uint8_t* out, std::uint32_t v) {
    for (int i = 0; i < 4; ++i)
        out[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void putU64(std::uint8_t* out, std::uint64_t v) {
    for (int i = 0; i < 8; ++i)
        out[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
void putI32(std::uint8_t* out, std::int32_t v) {
    putU32(out, static_cast<std::uint32_t>(v));
}
void putF32(std::uint8_t* out, float v) {
    putU32(out, std::bit_cast<std::uint32_t>(v));
}
void putF64(std::uint8_t* out, double v) {
    putU64(out, std::bit_cast<std::uint64_t>(v));
}

std::uint32_t getU32(const std::uint8_t* in) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i)
        v |= std::uint32_t{in[i]} << (8 * i);
    return v;
}
std::uint64_t getU64(const std::uint8_t* in) {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v |= std::uint64_t{in[i]} << (8 * i);
    return v;
}
std::int32_t getI32(const std::uint8_t* in) {
    return static_cast<std::int32_t>(getU32(in));
}
float getF32(const std::uint8_t* in) {
    return std::bit_cast<float>(getU32(in));
}
double getF64(const std::uint8_t* in) {
    return std::bit_cast<double>(getU64(in));
}

[[noreturn]] void fail(const std::string& message) {
    throw InputError(message);
}

const char* axisName(int axis) {
    return axis == 0 ? "x" : axis == 1 ? "y" : "z";
}

// Strict UTF-8 check (no overlongs, no surrogates, nothing above U+10FFFF).
bool isValidUtf8(const std::string& s) {
    std::size_t i = 0;
    while (i < s.size()) {
        const auto b0 = static_cast<unsigned char>(s[i]);
        std::size_t n = 0;
        std::uint32_t cp = 0;
        if (b0 < 0x80) {
            ++i;
            continue;
        }
        if (b0 >= 0xC2 && b0 <= 0xDF) {
            n = 1;
            cp = b0 & 0x1Fu;
        } else if (b0 >= 0xE0 && b0 <= 0xEF) {
            n = 2;
            cp = b0 & 0x0Fu;
        } else if (b0 >= 0xF0 && b0 <= 0xF4) {
            n = 3;
            cp = b0 & 0x07u;
        } else {
            return false;
        }
        if (i + n >= s.size()) return false; // sequence runs past the end
        for (std::size_t k = 1; k <= n; ++k) {
            const auto b = static_cast<unsigned char>(s[i + k]);
            if ((b & 0xC0u) != 0x80u) return false;
            cp = (cp << 6) | (b & 0x3Fu);
        }
        if ((n == 2 && (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF))) ||
            (n == 3 && (cp < 0x10000 || cp > 0x10FFFF)))
            return false;
        i += n + 1;
    }
    return true;
}

// The checks shared by writer and reader on everything but the byte framing, so the writer never
// produces a file the reader rejects.
void validateHeaderFields(const VotSpace& s) {
    for (int a = 0; a < 3; ++a) {
        if (s.dims[a] < 1)
            fail(std::string("grid size along ") + axisName(a) + " is " + std::to_string(s.dims[a]));
        if (!std::isfinite(s.origin[a]))
            fail(std::string("origin ") + axisName(a) + " is not a finite number");
        if (!std::isfinite(s.spacing[a]) || !(s.spacing[a] > 0.0))
            fail(std::string("spacing ") + axisName(a) + " is not a positive finite number");
    }
    if (s.degree < 0 || s.degree > 3) fail("degree " + std::to_string(s.degree) + " is outside 0..3");
    if (!std::isfinite(s.eps) || s.eps < 0.f) fail("eps is not a finite number >= 0");
    // -inf means "no background": every cell is covered.
    if (std::isnan(s.background) || s.background == std::numeric_limits<float>::infinity())
        fail("background is NaN or +infinity");
    if (!isValidUtf8(s.metaJson)) fail("meta block is not valid UTF-8");
}

void validateVot(const VotSpace& s, const Vot& v, std::size_t index) {
    const std::string where = "Vot " + std::to_string(index) + ": ";
    for (int a = 0; a < 3; ++a) {
        if (v.box.lo[a] >= v.box.hi[a])
            fail(where + "box lo >= hi along " + axisName(a) + " (" + std::to_string(v.box.lo[a]) +
                 " >= " + std::to_string(v.box.hi[a]) + ")");
        if (v.box.lo[a] < 0 || v.box.hi[a] >= s.dims[a])
            fail(where + "box [" + std::to_string(v.box.lo[a]) + ", " + std::to_string(v.box.hi[a]) +
                 "] along " + axisName(a) + " is outside the grid of " + std::to_string(s.dims[a]) +
                 " points");
        if (!std::isfinite(v.p[a])) fail(where + "expansion point is not finite");
    }
    if (!std::isfinite(v.err) || v.err < 0.f) fail(where + "err is not a finite number >= 0");
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i) {
        if (!std::isfinite(v.c[i])) fail(where + "coefficient " + MONOMIAL_NAMES[i] + " is not finite");
        // docs/DESIGN.md §2: the header degree bounds every nonzero stored coefficient, so a reader that
        // evaluates up to the header's degree is always right.
        if (v.c[i] != 0.f && monomialDegree(i) > s.degree)
            fail(where + "coefficient " + MONOMIAL_NAMES[i] + " is nonzero but the header degree is " +
                 std::to_string(s.degree));
    }
}

void validateSpace(const VotSpace& s) {
    validateHeaderFields(s);
    for (std::size_t i = 0; i < s.vots.size(); ++i)
        validateVot(s, s.vots[i], i);
}

void encodeVot(std::uint8_t* rec, const Vot& v) {
    for (int a = 0; a < 3; ++a) {
        putI32(rec + REC_LO + 4 * a, v.box.lo[a]);
        putI32(rec + REC_HI + 4 * a, v.box.hi[a]);
        putF32(rec + REC_P + 4 * a, v.p[a]);
    }
    putF32(rec + REC_ERR, v.err);
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        putF32(rec + REC_C + 4 * i, v.c[i]);
}

Vot decodeVot(const std::uint8_t* rec) {
    Vot v;
    for (int a = 0; a < 3; ++a) {
        v.box.lo[a] = getI32(rec + REC_LO + 4 * a);
        v.box.hi[a] = getI32(rec + REC_HI + 4 * a);
        v.p[a] = getF32(rec + REC_P + 4 * a);
    }
    v.err = getF32(rec + REC_ERR);
    for (std::size_t i = 0; i < MONOMIAL_COUNT; ++i)
        v.c[i] = getF32(rec + REC_C + 4 * i);
    return v;
}

// Magic, version, header size, and that vot_count and meta_bytes add up to the file length.
// Returns the meta block size. Guards against overflow from absurd counts.
std::uint64_t checkFraming(const std::uint8_t* data, std::size_t size) {
    if (size < VOTS_MAGIC.size() || std::memcmp(data + OFF_MAGIC, VOTS_MAGIC.data(), VOTS_MAGIC.size()) != 0)
        fail("not a Vot-Space file (the first 4 bytes are not \"VOTS\")");
    if (size < VOTS_HEADER_BYTES + CRC_BYTES)
        fail("file is " + std::to_string(size) + " bytes, shorter than the " +
             std::to_string(VOTS_HEADER_BYTES) + "-byte header plus checksum (truncated?)");
    const std::uint32_t version = getU32(data + OFF_VERSION);
    if (version != VOTS_FILE_VERSION)
        fail("unsupported Vot-Space file version " + std::to_string(version) +
             " (this build reads version 1)");
    const std::uint32_t headerBytes = getU32(data + OFF_HEADER_BYTES);
    if (headerBytes != VOTS_HEADER_BYTES)
        fail("header size field is " + std::to_string(headerBytes) + ", expected 128");
    const std::uint64_t count = getU64(data + OFF_VOT_COUNT);
    const std::uint64_t metaBytes = getU64(data + OFF_META_BYTES);
    const std::uint64_t body = size - VOTS_HEADER_BYTES - CRC_BYTES; // records + meta
    const bool fits = metaBytes <= body && count <= (body - metaBytes) / VOTS_RECORD_BYTES &&
                      count * VOTS_RECORD_BYTES + metaBytes == body;
    if (!fits)
        fail("file length " + std::to_string(size) + " does not match the header (" + std::to_string(count) +
             " Vots, " + std::to_string(metaBytes) + " meta bytes): truncated or corrupt");
    return metaBytes;
}

} // namespace

namespace {

/// The 128-byte header of a file of `space`'s fields, `votCount` records and its meta block.
void encodeHeader(std::uint8_t* h, const VotSpace& space, std::uint64_t votCount) {
    std::memcpy(h + OFF_MAGIC, VOTS_MAGIC.data(), VOTS_MAGIC.size());
    putU32(h + OFF_VERSION, VOTS_FILE_VERSION);
    putU32(h + OFF_HEADER_BYTES, static_cast<std::uint32_t>(VOTS_HEADER_BYTES));
    for (int a = 0; a < 3; ++a) {
        putU32(h + OFF_DIMS + 4 * a, static_cast<std::uint32_t>(space.dims[a]));
        putF64(h + OFF_ORIGIN + 8 * a, space.origin[a]);
        putF64(h + OFF_SPACING + 8 * a, space.spacing[a]);
    }
    putU32(h + OFF_DEGREE, static_cast<std::uint32_t>(space.degree));
    putF32(h + OFF_EPS, space.eps);
    putF32(h + OFF_BACKGROUND, space.background);
    putU32(h + OFF_FLAGS, space.epsVaries ? VotSpace::FLAG_EPS_VARIES : 0u);
    putU64(h + OFF_VOT_COUNT, votCount);
    putU64(h + OFF_META_BYTES, space.metaJson.size());
    // Reserved bytes 104..127 stay zero.
}

void encodeVots(std::uint8_t* rec, const std::vector<Vot>& vots) {
    for (const Vot& v : vots) {
        encodeVot(rec, v);
        rec += VOTS_RECORD_BYTES;
    }
}

} // namespace

std::vector<std::uint8_t> encodeVotSpace(const VotSpace& space) {
    validateSpace(space);
    const std::size_t records = space.vots.size() * VOTS_RECORD_BYTES;
    std::vector<std::uint8_t> out(VOTS_HEADER_BYTES + records + space.metaJson.size() + CRC_BYTES, 0);
    std::uint8_t* h = out.data();
    encodeHeader(h, space, space.vots.size());
    encodeVots(h + VOTS_HEADER_BYTES, space.vots);
    std::uint8_t* meta = h + VOTS_HEADER_BYTES + records;
    if (!space.metaJson.empty()) std::memcpy(meta, space.metaJson.data(), space.metaJson.size());
    const std::size_t crcAt = out.size() - CRC_BYTES;
    putU32(h + crcAt, crc32Update(0, h, crcAt));
    return out;
}

VotRecords encodeVotRecords(const VotSpace& space) {
    validateSpace(space);
    VotRecords records;
    records.bytes.assign(space.vots.size() * VOTS_RECORD_BYTES, 0);
    encodeVots(records.bytes.data(), space.vots);
    records.crc = crc32Update(0, records.bytes.data(), records.bytes.size());
    return records;
}

VotSpaceFrame encodeVotSpaceFrame(const VotSpace& space, const std::vector<VotRecordsPart>& parts) {
    validateHeaderFields(space);
    std::uint64_t recordBytes = 0;
    for (const VotRecordsPart& part : parts) {
        if (part.bytes % VOTS_RECORD_BYTES != 0)
            fail("a part of " + std::to_string(part.bytes) + " bytes is not whole records");
        recordBytes += part.bytes;
    }
    VotSpaceFrame frame;
    frame.header.assign(VOTS_HEADER_BYTES, 0);
    encodeHeader(frame.header.data(), space, recordBytes / VOTS_RECORD_BYTES);
    std::uint32_t crc = crc32Update(0, frame.header.data(), frame.header.size());
    for (const VotRecordsPart& part : parts)
        crc = combineCrc(crc, part.crc, part.bytes);
    frame.tail.assign(space.metaJson.begin(), space.metaJson.end());
    crc = crc32Update(crc, frame.tail.data(), frame.tail.size());
    frame.tail.resize(frame.tail.size() + CRC_BYTES);
    putU32(frame.tail.data() + frame.tail.size() - CRC_BYTES, crc);
    frame.tailAt = VOTS_HEADER_BYTES + recordBytes;
    return frame;
}

VotSpace decodeVotSpaceWithoutMeta(const std::uint8_t* data, std::size_t size) {
    if (data == nullptr) size = 0;
    const std::uint64_t metaBytes = checkFraming(data, size);
    const std::size_t crcAt = size - CRC_BYTES;
    const std::uint32_t stored = getU32(data + crcAt);
    const std::uint32_t actual = crc32Update(0, data, crcAt);
    if (stored != actual) fail("checksum mismatch (file is corrupt)");

    for (std::size_t i = OFF_RESERVED; i < VOTS_HEADER_BYTES; ++i)
        if (data[i] != 0) fail("reserved header byte " + std::to_string(i) + " is not zero");
    const std::uint32_t flags = getU32(data + OFF_FLAGS);
    if ((flags & ~KNOWN_FLAGS) != 0) fail("unknown header flags " + std::to_string(flags));

    VotSpace s;
    for (int a = 0; a < 3; ++a) {
        const std::uint32_t d = getU32(data + OFF_DIMS + 4 * a);
        if (d == 0 || d > static_cast<std::uint32_t>(INT_MAX))
            fail(std::string("grid size along ") + axisName(a) + " is " + std::to_string(d));
        s.dims[a] = static_cast<int>(d);
        s.origin[a] = getF64(data + OFF_ORIGIN + 8 * a);
        s.spacing[a] = getF64(data + OFF_SPACING + 8 * a);
    }
    const std::uint32_t degree = getU32(data + OFF_DEGREE);
    if (degree > 3) fail("degree " + std::to_string(degree) + " is outside 0..3");
    s.degree = static_cast<int>(degree);
    s.eps = getF32(data + OFF_EPS);
    s.background = getF32(data + OFF_BACKGROUND);
    s.epsVaries = (flags & VotSpace::FLAG_EPS_VARIES) != 0;
    const std::size_t count = static_cast<std::size_t>(getU64(data + OFF_VOT_COUNT));
    const std::uint8_t* meta = data + VOTS_HEADER_BYTES + count * VOTS_RECORD_BYTES;
    s.metaJson.assign(reinterpret_cast<const char*>(meta), static_cast<std::size_t>(metaBytes));
    validateHeaderFields(s);

    s.vots.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        s.vots.push_back(decodeVot(data + VOTS_HEADER_BYTES + i * VOTS_RECORD_BYTES));
        validateVot(s, s.vots.back(), i);
    }
    return s;
}

} // namespace vots::fit
