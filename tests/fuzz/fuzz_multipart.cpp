// libFuzzer target: the streaming multipart/related splitter on arbitrary bodies, fed in arbitrary chunks,
// must hand on parts or throw InputError, and never hold more than its bound besides one chunk.
#include "vots/fit/Error.h"
#include "vots/pacs/MultipartSplitter.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 2) return 0;
    // The first byte picks the chunk size (1..256), the second the boundary's length (1..16 of "abc...").
    const std::size_t chunk = static_cast<std::size_t>(data[0]) + 1;
    const std::string boundary = std::string("0123456789abcdef").substr(0, (data[1] % 16) + 1);
    const char* body = reinterpret_cast<const char*>(data + 2);
    const std::size_t length = size - 2;
    std::size_t partBytes = 0, begun = 0, ended = 0;
    try {
        vots::pacs::MultipartSplitter splitter(boundary, {[&](const vots::pacs::PartHeaders&) { ++begun; },
                                                          [&](const char*, std::size_t n) { partBytes += n; },
                                                          [&] { ++ended; }});
        for (std::size_t at = 0; at < length; at += chunk)
            splitter.feed(body + at, std::min(chunk, length - at));
        splitter.finish();
        if (ended != splitter.partsCompleted() || begun < ended || partBytes > length) std::abort();
    } catch (const vots::fit::InputError&) {
    }
    try {
        (void)vots::pacs::multipartBoundary(std::string(body, std::min<std::size_t>(length, 400)));
    } catch (const vots::fit::InputError&) {
    }
    return 0;
}
