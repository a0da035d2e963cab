// Vot-Space file v1 codec: bit-exact round trip, pinned byte layout, and rejection of every corruption.
#include "vots/fit/Error.h"
#include "vots/fit/VotSpaceFile.h"

#include "VotSpaceBytes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>

namespace vots::fit {
namespace {

using test::Bytes;
using test::fixCrc;
using test::makeSampleSpace;
using test::peekF32;
using test::peekF64;
using test::peekLE;
using test::pokeF32;
using test::pokeF64;
using test::pokeLE;

constexpr std::size_t H = VOTS_HEADER_BYTES;
constexpr std::size_t R = VOTS_RECORD_BYTES;

VotSpace decode(const Bytes& b) {
    return decodeVotSpaceWithoutMeta(b.data(), b.size());
}

/// Expects an InputError whose message is one line containing `needle`.
void expectRejected(const Bytes& b, const std::string& needle, const std::string& what) {
    try {
        decode(b);
        ADD_FAILURE() << what << ": accepted";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(needle), std::string::npos) << what << ": message was: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << what << ": message spans lines: " << msg;
    }
}

void expectSameBits(float a, float b, const std::string& what) {
    std::uint32_t ua = 0, ub = 0;
    std::memcpy(&ua, &a, 4);
    std::memcpy(&ub, &b, 4);
    EXPECT_EQ(ua, ub) << what;
}

TEST(VotSpaceFile, RoundTripIsBitExact) {
    const VotSpace in = makeSampleSpace(5);
    const Bytes bytes = encodeVotSpace(in);
    const VotSpace out = decode(bytes);
    EXPECT_EQ(encodeVotSpace(out), bytes);

    EXPECT_EQ(out.dims, in.dims);
    EXPECT_EQ(out.origin, in.origin);
    EXPECT_EQ(out.spacing, in.spacing);
    EXPECT_EQ(out.degree, in.degree);
    expectSameBits(out.eps, in.eps, "eps");
    expectSameBits(out.background, in.background, "background");
    EXPECT_EQ(out.epsVaries, in.epsVaries);
    EXPECT_EQ(out.metaJson, in.metaJson);
    ASSERT_EQ(out.vots.size(), in.vots.size());
    for (std::size_t i = 0; i < in.vots.size(); ++i) {
        EXPECT_EQ(out.vots[i].box, in.vots[i].box) << "vot " << i;
        for (int a = 0; a < 3; ++a)
            expectSameBits(out.vots[i].p[a], in.vots[i].p[a], "p");
        expectSameBits(out.vots[i].err, in.vots[i].err, "err");
        for (std::size_t c = 0; c < MONOMIAL_COUNT; ++c)
            expectSameBits(out.vots[i].c[c], in.vots[i].c[c], "c[" + std::to_string(c) + "]");
    }
}

TEST(VotSpaceFile, EmptySpaceRoundTrips) {
    VotSpace in;
    in.dims = {2, 2, 2};
    in.metaJson.clear();
    in.background = -std::numeric_limits<float>::infinity(); // "no background"
    const Bytes bytes = encodeVotSpace(in);
    ASSERT_EQ(bytes.size(), H + 4);
    const VotSpace out = decode(bytes);
    EXPECT_TRUE(out.vots.empty());
    EXPECT_TRUE(out.metaJson.empty());
    EXPECT_TRUE(std::isinf(out.background) && out.background < 0.f);
}

TEST(VotSpaceFile, HeaderAndRecordOffsetsArePinned) {
    const VotSpace s = makeSampleSpace(3);
    const Bytes b = encodeVotSpace(s);
    ASSERT_EQ(b.size(), H + 3 * R + s.metaJson.size() + 4);
    EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "VOTS");
    EXPECT_EQ(peekLE(b, 4, 4), 1u);
    EXPECT_EQ(peekLE(b, 8, 4), 128u);
    EXPECT_EQ(peekLE(b, 12, 4), 10u);
    EXPECT_EQ(peekLE(b, 16, 4), 8u);
    EXPECT_EQ(peekLE(b, 20, 4), 6u);
    EXPECT_EQ(peekF64(b, 24), -12.5);
    EXPECT_EQ(peekF64(b, 32), 0.25);
    EXPECT_EQ(peekF64(b, 40), 1e-3);
    EXPECT_EQ(peekF64(b, 48), 0.957);
    EXPECT_EQ(peekF64(b, 64), 1.5);
    EXPECT_EQ(peekLE(b, 72, 4), 3u);
    EXPECT_EQ(peekF32(b, 76), 2.5f);
    EXPECT_EQ(peekF32(b, 80), -200.f);
    EXPECT_EQ(peekLE(b, 84, 4), 1u);
    EXPECT_EQ(peekLE(b, 88, 8), 3u);
    EXPECT_EQ(peekLE(b, 96, 8), s.metaJson.size());
    for (std::size_t i = 104; i < 128; ++i)
        EXPECT_EQ(b[i], 0) << "reserved byte " << i;

    for (std::size_t v = 0; v < 3; ++v) {
        const std::size_t r = H + v * R; // record stride 120
        const Vot& vot = s.vots[v];
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(static_cast<std::int32_t>(peekLE(b, r + 4 * a, 4)), vot.box.lo[a]);
            EXPECT_EQ(static_cast<std::int32_t>(peekLE(b, r + 12 + 4 * a, 4)), vot.box.hi[a]);
            EXPECT_EQ(peekF32(b, r + 24 + 4 * a), vot.p[a]);
        }
        EXPECT_EQ(peekF32(b, r + 36), vot.err);
        for (std::size_t c = 0; c < MONOMIAL_COUNT; ++c)
            expectSameBits(peekF32(b, r + 40 + 4 * c), vot.c[c], "c");
    }
    const std::size_t metaAt = H + 3 * R;
    EXPECT_EQ(std::string(b.begin() + metaAt, b.end() - 4), s.metaJson);
    EXPECT_EQ(peekLE(b, b.size() - 4, 4), test::referenceCrc32(b.data(), b.size() - 4));
}

TEST(VotSpaceFile, NegativeBoxCoordinatesAreTwosComplement) {
    Bytes b = encodeVotSpace(makeSampleSpace(1));
    pokeLE(b, H, 0xFFFFFFFFu, 4); // lo.x = -1
    fixCrc(b);
    expectRejected(b, "outside the grid", "lo.x = -1");
}

TEST(VotSpaceFile, EveryFlippedByteIsRejected) {
    const Bytes good = encodeVotSpace(makeSampleSpace(3));
    for (std::size_t i = 0; i < good.size(); ++i) {
        for (const std::uint8_t mask : {std::uint8_t{0x01}, std::uint8_t{0x80}, std::uint8_t{0xFF}}) {
            Bytes b = good;
            b[i] ^= mask;
            EXPECT_THROW(decode(b), InputError) << "byte " << i << " mask " << int{mask};
        }
    }
}

TEST(VotSpaceFile, EveryTruncationIsRejected) {
    const Bytes good = encodeVotSpace(makeSampleSpace(3));
    for (std::size_t n = 0; n < good.size(); ++n) {
        const Bytes b(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
        EXPECT_THROW(decodeVotSpaceWithoutMeta(b.data(), b.size()), InputError) << "length " << n;
    }
    expectRejected(Bytes(good.begin(), good.begin() + 100), "shorter than", "100 bytes");
    EXPECT_THROW(decodeVotSpaceWithoutMeta(nullptr, 0), InputError);
}

TEST(VotSpaceFile, TrailingBytesAreRejected) {
    Bytes b = encodeVotSpace(makeSampleSpace(2));
    b.insert(b.end() - 4, 7, 'x'); // garbage before the CRC; CRC fixed so the length check fires
    fixCrc(b);
    expectRejected(b, "does not match", "7 extra bytes");
}

TEST(VotSpaceFile, WrongCountIsRejectedEvenWithValidCrc) {
    const Bytes good = encodeVotSpace(makeSampleSpace(3));
    // 3 + 2^61 Vots: 120 * count overflows 64 bits to exactly the true record length.
    const std::uint64_t overflowing = 3u + (std::uint64_t{1} << 61);
    for (const std::uint64_t count : {std::uint64_t{0}, std::uint64_t{2}, std::uint64_t{4}, overflowing,
                                      std::numeric_limits<std::uint64_t>::max()}) {
        Bytes b = good;
        pokeLE(b, 88, count, 8);
        fixCrc(b);
        expectRejected(b, "does not match", "count " + std::to_string(count));
    }
    for (const std::uint64_t meta : {std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max() - 100}) {
        Bytes b = good;
        pokeLE(b, 96, meta, 8);
        fixCrc(b);
        expectRejected(b, "does not match", "meta_bytes " + std::to_string(meta));
    }
}

TEST(VotSpaceFile, CrcMismatchIsNamed) {
    Bytes b = encodeVotSpace(makeSampleSpace(2));
    b[H + 40] ^= 0x10; // a coefficient bit
    expectRejected(b, "checksum", "flipped coefficient bit");
}

struct Corruption {
    const char* name;
    std::function<void(Bytes&)> edit;
    const char* message;
};

TEST(VotSpaceFile, EachInvalidFieldIsRejectedWithValidCrc) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::size_t r1 = H + R; // second record
    const std::vector<Corruption> cases = {
        {"magic", [](Bytes& b) { b[3] = 'X'; }, "not a Vot-Space file"},
        {"version 2", [](Bytes& b) { pokeLE(b, 4, 2, 4); }, "version 2"},
        {"version 0", [](Bytes& b) { pokeLE(b, 4, 0, 4); }, "version 0"},
        {"header_bytes 64", [](Bytes& b) { pokeLE(b, 8, 64, 4); }, "header size"},
        {"dims.y 0", [](Bytes& b) { pokeLE(b, 16, 0, 4); }, "grid size along y"},
        {"dims.z 2^31", [](Bytes& b) { pokeLE(b, 20, 0x80000000u, 4); }, "grid size along z"},
        {"origin inf", [&](Bytes& b) { pokeF64(b, 32, inf); }, "origin y"},
        {"spacing 0", [](Bytes& b) { pokeF64(b, 48, 0.0); }, "spacing x"},
        {"spacing < 0", [](Bytes& b) { pokeF64(b, 56, -1.0); }, "spacing y"},
        {"spacing NaN", [&](Bytes& b) { pokeF64(b, 64, nan); }, "spacing z"},
        {"degree 4", [](Bytes& b) { pokeLE(b, 72, 4, 4); }, "degree 4"},
        {"eps NaN", [&](Bytes& b) { pokeF32(b, 76, nan); }, "eps"},
        {"eps inf", [&](Bytes& b) { pokeF32(b, 76, inf); }, "eps"},
        {"eps < 0", [](Bytes& b) { pokeF32(b, 76, -1.f); }, "eps"},
        {"background NaN", [&](Bytes& b) { pokeF32(b, 80, nan); }, "background"},
        {"unknown flag", [](Bytes& b) { pokeLE(b, 84, 5, 4); }, "flags"},
        {"reserved", [](Bytes& b) { b[127] = 1; }, "reserved header byte 127"},
        {"hi.x = dims", [&](Bytes& b) { pokeLE(b, r1 + 12, 10, 4); }, "outside the grid"},
        {"hi.z huge", [&](Bytes& b) { pokeLE(b, r1 + 20, 0x7FFFFFFF, 4); }, "outside the grid"},
        {"lo.y < 0", [&](Bytes& b) { pokeLE(b, r1 + 4, 0xFFFFFFF0u, 4); }, "outside the grid"},
        {"lo == hi", [&](Bytes& b) { pokeLE(b, r1 + 8, peekLE(b, r1 + 20, 4), 4); }, "lo >= hi"},
        {"lo > hi", [&](Bytes& b) { pokeLE(b, r1 + 0, 9, 4); }, "lo >= hi"},
        {"p NaN", [&](Bytes& b) { pokeF32(b, r1 + 28, nan); }, "expansion point"},
        {"err inf", [&](Bytes& b) { pokeF32(b, r1 + 36, inf); }, "err"},
        {"err < 0", [&](Bytes& b) { pokeF32(b, r1 + 36, -0.5f); }, "err"},
        {"c NaN", [&](Bytes& b) { pokeF32(b, r1 + 40 + 4 * 7, nan); }, "coefficient xy"},
        {"c -inf", [&](Bytes& b) { pokeF32(b, r1 + 40, -inf); }, "coefficient 1"},
        {"meta not UTF-8", [](Bytes& b) { b[b.size() - 6] = 0xC3; }, "UTF-8"},
    };
    const Bytes good = encodeVotSpace(makeSampleSpace(3));
    for (const Corruption& c : cases) {
        Bytes b = good;
        c.edit(b);
        fixCrc(b);
        expectRejected(b, c.message, c.name);
    }
}

TEST(VotSpaceFile, MessagesNameTheVot) {
    Bytes b = encodeVotSpace(makeSampleSpace(3));
    pokeF32(b, H + 2 * R + 40, std::numeric_limits<float>::quiet_NaN());
    fixCrc(b);
    expectRejected(b, "Vot 2", "NaN in third record");
}

TEST(VotSpaceFile, HeaderDegreeBoundsStoredCoefficients) {
    VotSpace s = makeSampleSpace(2);
    s.degree = 1; // but the sample Vots carry nonzero quadratic and cubic terms
    EXPECT_THROW(encodeVotSpace(s), InputError);
    for (Vot& v : s.vots)
        for (std::size_t c = 0; c < MONOMIAL_COUNT; ++c)
            if (monomialDegree(c) > 1) v.c[c] = 0.f;
    Bytes b = encodeVotSpace(s);
    EXPECT_EQ(decode(b).degree, 1);
    pokeF32(b, H + 40 + 4 * 19, 1.f); // c_xyz of record 0
    fixCrc(b);
    expectRejected(b, "coefficient xyz is nonzero but the header degree is 1", "cubic term at degree 1");
}

TEST(VotSpaceFile, WriterRejectsWhatTheReaderWould) {
    const auto rejects = [](const std::function<void(VotSpace&)>& edit) {
        VotSpace s = makeSampleSpace(2);
        edit(s);
        EXPECT_THROW(encodeVotSpace(s), InputError);
    };
    rejects([](VotSpace& s) { s.vots[1].c[3] = std::numeric_limits<float>::quiet_NaN(); });
    rejects([](VotSpace& s) { s.vots[0].box.hi[0] = s.dims[0]; });
    rejects([](VotSpace& s) { s.vots[0].box.lo[2] = s.vots[0].box.hi[2]; });
    rejects([](VotSpace& s) { s.vots[0].box.lo[1] = -1; });
    rejects([](VotSpace& s) { s.dims[2] = 0; });
    rejects([](VotSpace& s) { s.spacing[0] = 0.0; });
    rejects([](VotSpace& s) { s.origin[1] = std::numeric_limits<double>::quiet_NaN(); });
    rejects([](VotSpace& s) { s.degree = 4; });
    rejects([](VotSpace& s) { s.eps = std::numeric_limits<float>::infinity(); });
    rejects([](VotSpace& s) { s.metaJson = "\xFF"; });
}

TEST(VotSpaceFile, PartsWrittenApartAreTheWholeFileByteForByte) {
    const VotSpace whole = makeSampleSpace(7);
    // Three writers: the first two Vots, none (a rank without Vots), the other five.
    std::vector<VotSpace> parts(3, whole);
    parts[0].vots.assign(whole.vots.begin(), whole.vots.begin() + 2);
    parts[1].vots.clear();
    parts[2].vots.assign(whole.vots.begin() + 2, whole.vots.end());
    Bytes assembled;
    std::vector<VotRecordsPart> crcs;
    std::vector<Bytes> records;
    for (VotSpace& part : parts) {
        part.metaJson.clear(); // only the frame's writer has the meta block
        const VotRecords encoded = encodeVotRecords(part);
        crcs.push_back({encoded.crc, encoded.bytes.size()});
        records.push_back(encoded.bytes);
    }
    const VotSpaceFrame frame = encodeVotSpaceFrame(whole, crcs);
    EXPECT_EQ(frame.tailAt, H + 7 * R);
    assembled = frame.header;
    for (const Bytes& r : records)
        assembled.insert(assembled.end(), r.begin(), r.end());
    assembled.insert(assembled.end(), frame.tail.begin(), frame.tail.end());
    EXPECT_EQ(assembled, encodeVotSpace(whole));

    // A part's records are checked as the whole file's are; a length that is not whole records is refused.
    VotSpace bad = parts[0];
    bad.vots[0].box.hi[0] = bad.dims[0];
    EXPECT_THROW(encodeVotRecords(bad), InputError);
    crcs[1].bytes = 7;
    EXPECT_THROW(encodeVotSpaceFrame(whole, crcs), InputError);
}

} // namespace
} // namespace vots::fit
