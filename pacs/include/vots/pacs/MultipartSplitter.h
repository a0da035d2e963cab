// A streaming splitter of multipart/related bodies (RFC 2046): parts come out as the bytes arrive.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>

namespace vots::pacs {

/// A part's header fields, names lower-cased; a repeated name keeps its last value.
using PartHeaders = std::map<std::string, std::string>;

/// What the splitter hands on: a part's headers once they are complete, its bytes in any number of
/// pieces, and its end. A handler may throw to stop the stream; the exception passes through feed().
struct MultipartHandlers {
    std::function<void(const PartHeaders&)> partBegin;
    std::function<void(const char* data, std::size_t size)> partData;
    std::function<void()> partEnd;
};

/// The boundary parameter of a Content-Type such as `multipart/related; type="application/dicom";
/// boundary=XYZ` (quoted or not). Throws fit::InputError when the type is not multipart or has no
/// boundary, or the boundary is not 1..70 characters.
std::string multipartBoundary(const std::string& contentType);

/// Feed it the body in chunks of any size; it holds at most one part-header block (MAX_HEADER_BYTES) and
/// a delimiter's length of bytes besides, never a whole part. Malformed input throws fit::InputError.
class MultipartSplitter {
public:
    static constexpr std::size_t MAX_HEADER_BYTES = 16384;

    MultipartSplitter(const std::string& boundary, MultipartHandlers handlers);

    /// The next bytes of the body.
    void feed(const char* data, std::size_t size);
    /// The body has ended: throws fit::InputError unless the closing delimiter was seen (a cut stream).
    void finish();
    /// Parts whose end has been handed on.
    std::size_t partsCompleted() const { return mPartsCompleted; }

private:
    enum class State { Preamble, AfterDelimiter, Padding, Headers, Data, Epilogue };

    void step();
    bool skipToFirstDelimiter();
    bool readAfterDelimiter();
    bool readPadding();
    bool readHeaders();
    bool readData();
    void parseHeaders(const std::string& block);

    std::string mDelimiter; // "\r\n--" + boundary
    MultipartHandlers mHandlers;
    State mState = State::Preamble;
    std::string mPending; // bytes not yet handed on
    std::size_t mPaddingBytes = 0;
    std::size_t mPartsCompleted = 0;
};

} // namespace vots::pacs
