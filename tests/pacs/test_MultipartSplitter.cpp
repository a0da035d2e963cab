// The streaming multipart/related splitter: parts, chunking anywhere, preamble, padding, cuts and bounds.
#include "vots/fit/Error.h"
#include "vots/pacs/MultipartSplitter.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using vots::pacs::MultipartSplitter;
using vots::pacs::PartHeaders;

struct Collected {
    std::vector<PartHeaders> headers;
    std::vector<std::string> bodies;
    int ended = 0;
};

/// Feeds `body` in chunks of `chunk` bytes (0: all at once) and finishes.
Collected split(const std::string& boundary, const std::string& body, std::size_t chunk = 0) {
    Collected c;
    MultipartSplitter splitter(boundary, {[&](const PartHeaders& h) {
                                              c.headers.push_back(h);
                                              c.bodies.emplace_back();
                                          },
                                          [&](const char* d, std::size_t n) { c.bodies.back().append(d, n); },
                                          [&] { ++c.ended; }});
    if (chunk == 0) chunk = body.size() + 1;
    for (std::size_t at = 0; at < body.size(); at += chunk)
        splitter.feed(body.data() + at, std::min(chunk, body.size() - at));
    splitter.finish();
    EXPECT_EQ(splitter.partsCompleted(), static_cast<std::size_t>(c.ended));
    return c;
}

std::string part(const std::string& boundary, const std::string& data,
                 const std::string& headers = "Content-Type: application/dicom\r\n") {
    return "--" + boundary + "\r\n" + headers + "\r\n" + data + "\r\n";
}

const std::string B = "abc123";

TEST(MultipartSplitter, SplitsPartsWithTheirHeadersAndBytes) {
    const std::string one(1000, '\x01'), two = "DICM\r\n--abc12\r\n--ab"; // data that resembles a delimiter
    const Collected c =
        split(B, part(B, one) + part(B, two, "Content-Type: application/dicom\r\nX-Extra:  v \r\n") + "--" +
                     B + "--\r\n");
    ASSERT_EQ(c.ended, 2);
    EXPECT_EQ(c.bodies[0], one);
    EXPECT_EQ(c.bodies[1], two);
    EXPECT_EQ(c.headers[0].at("content-type"), "application/dicom");
    EXPECT_EQ(c.headers[1].at("x-extra"), "v");
}

TEST(MultipartSplitter, GivesTheSamePartsForEveryChunkSize) {
    std::string data;
    for (int i = 0; i < 3000; ++i)
        data += static_cast<char>(i * 7 % 256);
    const std::string body = part(B, data) + part(B, data.substr(17)) + "--" + B + "--";
    for (std::size_t chunk : {1u, 2u, 3u, 5u, 7u, 8u, 9u, 64u, 1000u}) {
        const Collected c = split(B, body, chunk);
        ASSERT_EQ(c.ended, 2) << chunk;
        EXPECT_EQ(c.bodies[0], data) << chunk;
        EXPECT_EQ(c.bodies[1], data.substr(17)) << chunk;
    }
}

TEST(MultipartSplitter, SkipsThePreambleAndTheEpilogue) {
    const Collected c =
        split(B, "This is a preamble.\r\n" + part(B, "x") + "--" + B + "--\r\nepilogue --" + B + "\r\n", 3);
    ASSERT_EQ(c.ended, 1);
    EXPECT_EQ(c.bodies[0], "x");
}

TEST(MultipartSplitter, AcceptsTransportPaddingAfterABoundary) {
    const Collected c =
        split(B, "--" + B + " \t \r\nContent-Type: application/dicom\r\n\r\nxy\r\n--" + B + "--", 2);
    ASSERT_EQ(c.ended, 1);
    EXPECT_EQ(c.bodies[0], "xy");
}

TEST(MultipartSplitter, HandsOnAPartWithoutContentType) {
    const Collected c = split(B, part(B, "data", "") + "--" + B + "--");
    ASSERT_EQ(c.ended, 1);
    EXPECT_TRUE(c.headers[0].empty());
    EXPECT_EQ(c.bodies[0], "data");
}

TEST(MultipartSplitter, ACutStreamIsAnError) {
    EXPECT_THROW(split(B, part(B, "data")), vots::fit::InputError);             // no closing delimiter
    EXPECT_THROW(split(B, part(B, "da").substr(0, 20)), vots::fit::InputError); // cut inside a part
    EXPECT_THROW(split(B, ""), vots::fit::InputError);                          // nothing at all
    EXPECT_THROW(split(B, "just text"), vots::fit::InputError);                 // no delimiter ever
}

TEST(MultipartSplitter, RefusesMalformedBoundaryLinesAndHeaders) {
    EXPECT_THROW(split(B, "--" + B + "garbage\r\n\r\nx\r\n--" + B + "--"), vots::fit::InputError);
    EXPECT_THROW(split(B, "--" + B + "\r\nno colon here\r\n\r\nx\r\n--" + B + "--"), vots::fit::InputError);
}

TEST(MultipartSplitter, BoundsThePartHeaders) {
    const std::string huge = "X-Huge: " + std::string(MultipartSplitter::MAX_HEADER_BYTES + 10, 'a') + "\r\n";
    // Refused as soon as the bound is passed, without waiting for the end of the headers.
    MultipartSplitter splitter(B, {});
    const std::string start = "--" + B + "\r\n" + huge;
    EXPECT_THROW(splitter.feed(start.data(), start.size()), vots::fit::InputError);
}

TEST(MultipartSplitter, ReadsTheBoundaryOfAContentType) {
    using vots::pacs::multipartBoundary;
    EXPECT_EQ(multipartBoundary("multipart/related; type=\"application/dicom\"; boundary=abc"), "abc");
    EXPECT_EQ(multipartBoundary("Multipart/Related;boundary=\"a b\""), "a b");
    EXPECT_THROW(multipartBoundary("application/dicom"), vots::fit::InputError);
    EXPECT_THROW(multipartBoundary("multipart/related; type=\"application/dicom\""), vots::fit::InputError);
    EXPECT_THROW(multipartBoundary("multipart/related; boundary=" + std::string(71, 'x')),
                 vots::fit::InputError);
}

} // namespace
